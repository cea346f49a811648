#include "saliency/normalisation.h"

#include <utility>

#include "util/error.h"

namespace attend {

NormalisationRegistry::NormalisationRegistry() {
  const std::vector<std::pair<std::string, std::string>> built_in = {
      {"minmax", "(F - min) / (max - min) over the frame (SPEC 2.3)"},
      {"local_maxima", "Itti, Koch and Niebur's N(.): min-max times (1 - mean local maximum)^2"}};
  for (const auto& [name, summary] : built_in) {
    Entry entry;
    entry.name = name;
    entry.summary = summary;
    entry.origin = "built-in";
    entry.built_in = true;
    entry.normalise = [name = name](const cv::Mat& map, const SaliencyOptions& options,
                                    cv::Mat* out) {
      SaliencyOptions chosen = options;
      chosen.normalisation = name;
      NormaliseMap(map, chosen, out);
    };
    entries_.emplace(name, std::move(entry));
  }
}

void NormalisationRegistry::Add(const std::string& name, const std::string& summary,
                                const std::string& origin, MapNormalisation normalise) {
  if (name.empty()) throw ConfigError(origin + ": registers a normalisation with an empty name");
  const auto found = entries_.find(name);
  if (found != entries_.end()) {
    throw ConfigError(origin + ": registers normalisation '" + name + "', which " +
                      (found->second.built_in ? std::string("is built in")
                                              : found->second.origin + " already registered"));
  }
  Entry entry;
  entry.name = name;
  entry.summary = summary;
  entry.origin = origin;
  entry.normalise = [normalise = std::move(normalise)](const cv::Mat& map, const SaliencyOptions&,
                                                       cv::Mat* out) { normalise(map, out); };
  entries_.emplace(name, std::move(entry));
}

const NormalisationRegistry::Entry* NormalisationRegistry::Find(const std::string& name) const {
  const auto found = entries_.find(name);
  return found == entries_.end() ? nullptr : &found->second;
}

std::vector<std::string> NormalisationRegistry::Names() const {
  std::vector<std::string> names = SaliencyOptions::Normalisations();
  for (const auto& [name, entry] : entries_) {
    if (!entry.built_in) names.push_back(name);
  }
  return names;
}

}  // namespace attend
