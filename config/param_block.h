// A typed, read-tracking accessor over one YAML map: the only way modules, plugins and scene
// descriptions read YAML. Every getter records the key it was asked for, so that after a
// reader has asked for everything it knows, CheckNoUnknownKeys() reports any key that is left
// (a typo) with its file, line and the closest known key. Values out of range or of the wrong
// type are reported the same way. All failures throw ConfigError (exit status 2).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "util/range.h"

namespace attend {

class ParamBlock {
 public:
  // An empty block (no keys); getters return their defaults.
  ParamBlock();

  // Reads a YAML file whose top level is a map (or empty). Missing file, YAML syntax error,
  // duplicate key or a top level that is not a map: ConfigError naming the file and line.
  static ParamBlock LoadFile(const std::string& path);
  // Same for text in memory; `source` names it in messages.
  static ParamBlock Parse(const std::string& text, const std::string& source);

  // Applies one "key.path=value" override; the value is parsed as YAML, so lists and maps
  // work. List elements are addressed by index ("features.1.weight") or, for lists of maps
  // with a `name` key, by name ("features.skin.weight"). Only valid on the root block.
  void Override(const std::string& assignment);

  // Dotted key path of this block from the root ("" for the root, "features.2").
  const std::string& path() const;
  // Where a key (or, with "", this block) was written: "FILE:LINE" or "--set KEY=VALUE".
  // For a block, the overrides of keys inside it are named first.
  std::string Where(const std::string& key = "") const;
  // The file this block was read from.
  const std::string& source() const;

  bool Has(const std::string& key) const;
  // Keys present in this block, in file order.
  std::vector<std::string> Keys() const;

  bool GetBool(const std::string& key, bool default_value) const;
  int GetInt(const std::string& key, int default_value, Range range = {}) const;
  double GetDouble(const std::string& key, double default_value, Range range = {}) const;
  std::string GetString(const std::string& key, const std::string& default_value) const;
  // A string that must be one of `choices`.
  std::string GetChoice(const std::string& key, const std::string& default_value,
                        const std::vector<std::string>& choices) const;
  // Lists; `size` >= 0 requires exactly that many elements.
  std::vector<double> GetDoubles(const std::string& key, const std::vector<double>& default_value,
                                 Range range = {}, int size = -1) const;
  std::vector<int> GetInts(const std::string& key, const std::vector<int>& default_value,
                           Range range = {}, int size = -1) const;
  std::vector<std::string> GetStrings(const std::string& key,
                                      const std::vector<std::string>& default_value) const;
  // A count or seed of up to 64 bits: a plain integer in [0, max] (an int is 32 bits).
  std::uint64_t GetCount(const std::string& key, std::uint64_t default_value,
                         std::uint64_t max) const;

  // Like the getters above, but the key must be present.
  double RequireDouble(const std::string& key, Range range = {}) const;
  std::string RequireString(const std::string& key) const;

  // A nested map (an empty block when the key is absent or null).
  ParamBlock Child(const std::string& key) const;
  // A list of maps (empty when the key is absent or null).
  std::vector<ParamBlock> Children(const std::string& key) const;

  // A value of any type as YAML text in flow style ("3", "[1, 2]", "{a: 1}"), with where it
  // was written: what a reader that passes values on (a sweep's `--set KEY=VALUE`) keeps.
  struct Text {
    std::string text;
    std::string where;  // "FILE:LINE", or the --set that set it
  };
  // The value of `key` (which must be present) as text.
  Text ValueText(const std::string& key) const;
  // The elements of the list at `key` (absent or null: none), each as text with its own line;
  // a value that is not a list: ConfigError.
  std::vector<Text> ElementTexts(const std::string& key) const;
  // Whether `key` holds a list, or a map (false when absent).
  bool IsList(const std::string& key) const;
  bool IsMap(const std::string& key) const;

  // Throws ConfigError "WHERE: KEYPATH: message".
  [[noreturn]] void Fail(const std::string& key, const std::string& message) const;
  // Throws the error of an options struct's Check() ("window must be odd", "scales: each must
  // be ..."): at the key it starts with when this block has that key ("WHERE: KEYPATH: must
  // be odd"), else at the block with the whole message.
  [[noreturn]] void FailCheck(const std::string& error) const;

  // Throws ConfigError for the first key present that no getter asked for, naming it, its
  // line and the closest key that was asked for.
  void CheckNoUnknownKeys() const;
  // Records `key` as known whatever it holds, without reading it: a note for people that
  // attend never reads (a sequence.yaml's `generator`).
  void Accept(const std::string& key) const;

  // Keys that getters asked for, in the order asked (present or not).
  std::vector<std::string> KnownKeys() const;

  struct State;
  explicit ParamBlock(std::shared_ptr<State> state);
  const std::shared_ptr<State>& state() const { return state_; }

 private:
  // Dotted path of a key in this block.
  std::string KeyPath(const std::string& key) const;
  // "FILE:LINE" of a key (or, with "", this block) in the file, without the overrides.
  std::string WrittenAt(const std::string& key) const;

  std::shared_ptr<State> state_;
};

}  // namespace attend
