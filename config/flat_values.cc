#include "config/flat_values.h"

#include <yaml-cpp/yaml.h>

#include <set>

#include "config/param_block_yaml.h"

namespace attend {

namespace {

using FlatConfig = std::map<std::string, std::string>;

std::string ScalarText(const YAML::Node& node) {
  if (node.IsNull()) return "null";
  if (node.IsScalar()) return node.Scalar();
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

void Flatten(const YAML::Node& node, const std::string& prefix, FlatConfig* flat) {
  const auto join = [&prefix](const std::string& key) {
    return prefix.empty() ? key : prefix + "." + key;
  };
  if (node.IsMap()) {
    if (node.size() == 0 && !prefix.empty()) (*flat)[prefix] = "{}";
    for (const auto& entry : node) Flatten(entry.second, join(entry.first.Scalar()), flat);
    return;
  }
  if (node.IsSequence()) {
    bool all_scalars = true, all_named = node.size() > 0;
    std::set<std::string> names;
    for (const YAML::Node& item : node) {
      if (!item.IsScalar() && !item.IsNull()) all_scalars = false;
      if (!item.IsMap() || !item["name"] || !item["name"].IsScalar() ||
          !names.insert(item["name"].Scalar()).second) {
        all_named = false;
      }
    }
    if (all_scalars) {
      (*flat)[prefix] = ScalarText(node);
    } else if (all_named) {
      for (const YAML::Node& item : node) {
        const std::string base = join(item["name"].Scalar());
        for (const auto& entry : item) {
          if (entry.first.Scalar() == "name") continue;
          Flatten(entry.second, base + "." + entry.first.Scalar(), flat);
        }
        if (item.size() == 1) (*flat)[base] = "{}";
      }
    } else {
      for (std::size_t i = 0; i < node.size(); ++i) {
        Flatten(node[i], join(std::to_string(i)), flat);
      }
    }
    return;
  }
  (*flat)[prefix] = ScalarText(node);
}

}  // namespace

std::map<std::string, std::string> FlattenedValues(const ParamBlock& block) {
  FlatConfig flat;
  Flatten(NodeOf(block), "", &flat);
  return flat;
}

}  // namespace attend
