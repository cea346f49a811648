// A YAML file read as its nodes, each with the line it was written on, for files whose values
// are not an options struct's fields: a sweep file's parameter values (any YAML value, passed
// on as `--set` text) and its list of inputs. The text is checked as a ParamBlock first (UTF-8,
// syntax, duplicate keys, a map at the top), which also types the plain sections; the nodes
// give the rest. Errors are ConfigError "FILE:LINE: KEY: message", as ParamBlock's are.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "config/param_block.h"

namespace attend {

class YamlDocument {
 public:
  // `file` names the document in messages; relative paths in it are resolved from its folder.
  YamlDocument(const std::string& text, const std::string& file);

  // The top-level map; undefined or null for an empty document.
  const YAML::Node& root() const { return root_; }
  // The same document as a ParamBlock, for sections read by key (ReadFields).
  const ParamBlock& block() const { return block_; }
  const std::string& file() const { return file_; }

  // "FILE:LINE" of `node`.
  std::string At(const YAML::Node& node) const;
  // Throws ConfigError "FILE:LINE: KEY: message".
  [[noreturn]] void Fail(const YAML::Node& node, const std::string& key,
                         const std::string& message) const;
  // Every key of `map` must be one of `known`; `path` prefixes the keys in messages.
  void CheckKeys(const YAML::Node& map, const std::string& path,
                 const std::vector<std::string>& known) const;
  std::string String(const YAML::Node& node, const std::string& key) const;
  int Int(const YAML::Node& node, const std::string& key, int low, int high) const;
  // A non-empty path, relative ones taken from the file's folder, made absolute.
  std::string Path(const YAML::Node& node, const std::string& key) const;

 private:
  std::string file_;
  std::string folder_;
  ParamBlock block_;
  YAML::Node root_;
};

// `node` in YAML's flow style, the text a `--set KEY=VALUE` value takes.
std::string FlowText(const YAML::Node& node);

}  // namespace attend
