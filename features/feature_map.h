// Feature plugins (thesis 5.1.1, SPEC 2.3): each turns a frame context into a float map of the
// left image's size. Plugins are created by name from the registry, configured from their
// entry of the `features:` list, and may run concurrently on the same context.
//
// Writing one: derive from FeatureMap, read parameters in the factory through the ParamBlock
// (then call params.CheckNoUnknownKeys()), and register the factory, either in
// features/builtin.cc or from a shared library (features/plugin_api.h, docs/PLUGINS.md).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "config/feature_list.h"
#include "config/param_block.h"
#include "features/frame_context.h"
#include "saliency/normalisation.h"

namespace attend {

// What a plugin is told when a sequence starts.
struct SequenceStart {
  std::string name;  // the sequence's name (sequence.yaml, or its folder or video stem)
  cv::Size size;     // the frames' working size: every context of the sequence has it
  bool stereo = false;
  int first_frame = 0;  // the index of its first frame
};

// What a top-down channel recognised in a frame: a box in the frame's pixels (the object
// itself, not the detector's window), its label ("person", "face") and the detector's
// confidence mapped to (0, 1].
struct Detection {
  cv::Rect box;
  std::string label;
  float confidence = 0.f;
};

class FeatureMap {
 public:
  virtual ~FeatureMap() = default;
  // Called before the first frame of each sequence the plugin computes on, and after its last
  // frame, by the thread that computes the frames. A plugin that keeps state across frames
  // (a background, the previous frame) starts it afresh in BeginSequence.
  virtual void BeginSequence(const SequenceStart& start) { (void)start; }
  virtual void EndSequence() {}
  // Fills `out` with a CV_32FC1 map of context.size(): larger is more interesting. Called once
  // a frame, frames in order; other plugins may be computing on the same context at the same
  // time, so a plugin only reads the context. Any scale: saliency normalises every map.
  virtual void Compute(const FrameContext& context, cv::Mat* out) = 0;
  // True for features that need the right image; enabling one on a monocular source is a
  // configuration error (SPEC 3.1).
  virtual bool NeedsStereo() const { return false; }
  // A top-down channel's detections in the frame of the last Compute (features/detectors.h);
  // the attention stage labels its targets with them and may seed targets from them
  // (select.seed: detection). Empty for bottom-up features.
  virtual const std::vector<Detection>& detections() const {
    static const std::vector<Detection> none;
    return none;
  }
  // A top-down channel's cost in the last Compute: the pixels its detector searched (the
  // scaled images of a sliding-window detector, a network's inputs); -1 for features that
  // search for nothing. summary.json reports its mean a frame.
  virtual double searched_pixels() const { return -1.0; }
  // Whether Compute reads the context's AttentionRegions (where attention looked in the last
  // frame). `attend run` with two threads or more computes the features that do not while it
  // still tracks and selects in the frame before (pipeline/frame_pipeline.h); those that do
  // wait for it. A plugin that never reads them returns false, and runs ahead too.
  virtual bool ReadsAttentionRegions() const { return true; }
};

// What a factory may need to know about the run besides its own parameters.
struct FeatureSetup {
  bool stereo = true;  // the sequence has right images
  // Folder of the bundled files (configs/, sequences/); relative data paths in a plugin's
  // parameters are looked up in the current folder first, then here.
  std::string home;

  // `path` as given if absolute or present below the current folder, else below `home`; ""
  // when it is in neither place (or empty).
  std::string FindPath(const std::string& path) const;
  // FindPath(), or a ConfigError at `params.Where(key)` naming the places tried.
  std::string ResolvePath(const ParamBlock& params, const std::string& key,
                          const std::string& path) const;
  // "the current folder and in HOME", for messages about a path FindPath() did not find.
  std::string PlacesSearched() const;
};

// Reads the plugin's parameters from `params` (throwing ConfigError on bad values) and returns
// the plugin.
using FeatureFactory =
    std::function<std::unique_ptr<FeatureMap>(const ParamBlock& params, const FeatureSetup& setup)>;


class FeatureRegistry {
 public:
  struct Entry {
    std::string name;
    std::string summary;  // one line, for `attend features` style listings and messages
    FeatureFactory factory;
    std::string origin;  // "built-in" or the shared library that registered it
  };

  // Adds a plugin. A name already taken: ConfigError naming both origins.
  void Add(const std::string& name, const std::string& summary, FeatureFactory factory);
  // Origin given to plugins added from now on (the plugin loader sets the library path).
  void SetOrigin(const std::string& origin) { origin_ = origin; }

  const Entry* Find(const std::string& name) const;
  std::vector<std::string> Names() const;

  // Adds a normalisation (saliency/normalisation.h: it turns a feature's map, CV_32FC1 of any
  // scale, into CV_32FC1 of the same size in [0, 1]) under the current origin: a plugin
  // library adds its own in its register function, and `saliency.normalisation` or a
  // feature's `normalisation:` names it. A name already taken, built in or by another library:
  // ConfigError naming both.
  void AddNormalisation(const std::string& name, const std::string& summary,
                        MapNormalisation normalise);
  // Every normalisation: the built-in ones and the libraries'.
  const NormalisationRegistry& normalisations() const { return normalisations_; }

  // Creates the plugin of `spec` and checks that it read all of its parameters. An unknown
  // name: ConfigError at the entry's `name`, with the closest known name and the full list.
  std::unique_ptr<FeatureMap> Create(const FeatureSpec& spec, const FeatureSetup& setup) const;

 private:
  std::map<std::string, Entry> entries_;
  NormalisationRegistry normalisations_;
  std::string origin_ = "built-in";
};

// Checks a plugin's output: CV_32FC1, the frame's size, finite values. A violation is a
// ConfigError naming the plugin and its origin (a broken plugin was configured).
void CheckFeatureOutput(const FeatureRegistry::Entry& entry, const cv::Mat& map, cv::Size size);

}  // namespace attend
