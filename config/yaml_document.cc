#include "config/yaml_document.h"

#include <algorithm>
#include <filesystem>

#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace fs = std::filesystem;

YamlDocument::YamlDocument(const std::string& text, const std::string& file)
    : file_(file),
      folder_(fs::path(file).parent_path().string()),
      block_(ParamBlock::Parse(text, file)),
      root_(YAML::Load(text)) {}

std::string YamlDocument::At(const YAML::Node& node) const {
  return file_ + ":" + std::to_string(node.Mark().line + 1);
}

void YamlDocument::Fail(const YAML::Node& node, const std::string& key,
                        const std::string& message) const {
  throw ConfigError(At(node) + ": " + key + ": " + message);
}

void YamlDocument::CheckKeys(const YAML::Node& map, const std::string& path,
                             const std::vector<std::string>& known) const {
  for (const auto& entry : map) {
    const std::string key = entry.first.as<std::string>();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      Fail(entry.first, path.empty() ? key : path + "." + key,
           "unknown key" + DidYouMean(key, known) + " (known: " + Join(known, ", ") + ")");
    }
  }
}

std::string YamlDocument::String(const YAML::Node& node, const std::string& key) const {
  if (!node.IsScalar()) Fail(node, key, "expected a string");
  return node.as<std::string>();
}

int YamlDocument::Int(const YAML::Node& node, const std::string& key, int low, int high) const {
  int value = 0;
  if (!node.IsScalar() || !YAML::convert<int>::decode(node, value)) {
    Fail(node, key, "expected an integer");
  }
  if (value < low || value > high) {
    Fail(node, key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
  }
  return value;
}

std::string YamlDocument::Path(const YAML::Node& node, const std::string& key) const {
  const std::string text = String(node, key);
  if (text.empty()) Fail(node, key, "an empty path");
  fs::path path(text);
  if (path.is_relative()) path = fs::path(folder_) / path;
  return path.lexically_normal().string();
}

std::string FlowText(const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter << YAML::Flow << node;
  return emitter.c_str();
}

}  // namespace attend
