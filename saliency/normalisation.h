// The one registry of normalisations: how a feature map (CV_32FC1, any scale) becomes a map in
// [0, 1] before the maps are combined (SPEC 2.3). It holds the built-in ones (the table
// BuiltinNormalisations below) and those a plugin library registers
// (FeatureRegistry::AddNormalisation); `saliency.normalisation` and a feature's
// `normalisation:` key name any of them.
//
// Adding a built-in normalisation:
//   1. Write its function in saliency/normalisation.cc, with the signature of
//      BuiltinNormalisation::normalise (its parameters, if any, are SaliencyOptions fields).
//   2. Add its row {name, summary, function} to the table in BuiltinNormalisations().
// The names of `saliency.normalisation`, NormaliseMap and the registry all come from that table.
#pragma once

#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "saliency/saliency_options.h"

namespace attend {

// A plugin's normalisation: `out` is CV_32FC1 of the map's size, with values in [0, 1].
using MapNormalisation = std::function<void(const cv::Mat& map, cv::Mat* out)>;

// A built-in normalisation: its name, a line for listings, and its function, which fills `out`
// (CV_32FC1 of the map's size, [0, 1]) from `map` (CV_32FC1) with the saliency options'
// parameters (local_maxima_window).
struct BuiltinNormalisation {
  const char* name;
  const char* summary;
  void (*normalise)(const cv::Mat& map, const SaliencyOptions& options, cv::Mat* out);
};

// The built-in normalisations, minmax (the default) first: the one list of them.
const std::vector<BuiltinNormalisation>& BuiltinNormalisations();

class NormalisationRegistry {
 public:
  struct Entry {
    std::string name;
    std::string summary;
    std::string origin;  // "built-in" or the library that registered it
    // The built-ins read the saliency options (local_maxima_window); a plugin's ignores them.
    std::function<void(const cv::Mat& map, const SaliencyOptions& options, cv::Mat* out)> normalise;
    bool built_in = false;
  };

  // The registry with the built-in normalisations.
  NormalisationRegistry();

  // Adds a plugin's normalisation. An empty name, or one already taken (built in or by another
  // library): ConfigError naming `origin` and the other.
  void Add(const std::string& name, const std::string& summary, const std::string& origin,
           MapNormalisation normalise);
  const Entry* Find(const std::string& name) const;
  // Every name, the built-in ones first, then the plugins' in name order.
  std::vector<std::string> Names() const;

 private:
  std::map<std::string, Entry> entries_;
};

}  // namespace attend
