#include "features/feature_map.h"

#include <cmath>

#include <filesystem>
#include <utility>

#include "util/error.h"
#include "util/float_checks.h"
#include "util/strings.h"

namespace fs = std::filesystem;

namespace attend {

std::string FeatureSetup::FindPath(const std::string& path) const {
  if (path.empty()) return "";
  const fs::path given(path);
  if (fs::exists(given)) return path;
  if (!given.is_absolute() && !home.empty() && fs::exists(fs::path(home) / given)) {
    return (fs::path(home) / given).string();
  }
  return "";
}

std::string FeatureSetup::PlacesSearched() const {
  return home.empty() ? "the current folder" : "the current folder and in " + home;
}

std::string FeatureSetup::ResolvePath(const ParamBlock& params, const std::string& key,
                                      const std::string& path) const {
  if (path.empty()) params.Fail(key, "must not be empty");
  const std::string found = FindPath(path);
  if (found.empty()) {
    params.Fail(key,
                "no such file: " + path +
                    (fs::path(path).is_absolute() ? "" : " (looked in " + PlacesSearched() + ")"));
  }
  return found;
}

void FeatureRegistry::Add(const std::string& name, const std::string& summary,
                          FeatureFactory factory) {
  if (name.empty()) throw ConfigError(origin_ + ": registers a feature with an empty name");
  const auto found = entries_.find(name);
  if (found != entries_.end()) {
    throw ConfigError(origin_ + ": registers feature '" + name + "', which " +
                      found->second.origin + " already registered");
  }
  entries_[name] = Entry{name, summary, std::move(factory), origin_};
}

const FeatureRegistry::Entry* FeatureRegistry::Find(const std::string& name) const {
  const auto found = entries_.find(name);
  return found == entries_.end() ? nullptr : &found->second;
}

std::vector<std::string> FeatureRegistry::Names() const {
  std::vector<std::string> names;
  for (const auto& [name, entry] : entries_) names.push_back(name);
  return names;
}

void FeatureRegistry::AddNormalisation(const std::string& name, const std::string& summary,
                                       MapNormalisation normalise) {
  normalisations_.Add(name, summary, origin_, std::move(normalise));
}

std::unique_ptr<FeatureMap> FeatureRegistry::Create(const FeatureSpec& spec,
                                                    const FeatureSetup& setup) const {
  const Entry* entry = Find(spec.name);
  if (entry == nullptr) {
    spec.params.Fail("name", "unknown feature '" + spec.name + "'" +
                                 DidYouMean(spec.name, Names()) +
                                 "; known: " + Join(Names(), ", ") +
                                 " (out-of-tree features need their library in `plugins:`)");
  }
  std::unique_ptr<FeatureMap> feature = entry->factory(spec.params, setup);
  if (feature == nullptr) {
    throw ConfigError(spec.params.Where() + ": feature '" + spec.name + "' (" + entry->origin +
                      ") returned no plugin");
  }
  spec.params.CheckNoUnknownKeys();
  return feature;
}

void CheckFeatureOutput(const FeatureRegistry::Entry& entry, const cv::Mat& map, cv::Size size) {
  const std::string who = "feature '" + entry.name + "' (" + entry.origin + ")";
  // A plugin's wrong map is the plugin's failure (exit status 4, as a Python feature's); a
  // built-in feature's is attend's own bug.
  const auto fail = [&](const std::string& message) {
    if (entry.origin == "built-in") throw InternalError(message);
    throw PluginError(message);
  };
  if (map.type() != CV_32FC1 || map.size() != size) {
    fail(who + " returned a map of " + std::to_string(map.cols) + "x" + std::to_string(map.rows) +
         " type " + std::to_string(map.type()) + "; a feature map must be CV_32FC1 of the " +
         "frame's size " + std::to_string(size.width) + "x" + std::to_string(size.height));
  }
  if (!AllFloatsFinite(map)) {
    int count = 0;
    cv::Point first(-1, -1);
    for (int y = 0; y < map.rows; ++y) {
      const float* row = map.ptr<float>(y);
      for (int x = 0; x < map.cols; ++x) {
        if (std::isfinite(row[x])) continue;
        if (count++ == 0) first = cv::Point(x, y);
      }
    }
    const std::string at = " (first at x " + std::to_string(first.x) + ", y " +
                           std::to_string(first.y) + "; " + std::to_string(count) + " pixels)";
    fail(who + " returned a map with NaN or infinite values" + at +
         "; a feature map must be finite everywhere");
  }
}

}  // namespace attend
