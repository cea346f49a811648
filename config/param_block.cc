#include "config/param_block.h"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "config/param_block_yaml.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/strings.h"

namespace attend {

// The document a block belongs to: its file name and the overrides applied to it.
struct Document {
  std::string source;
  // Key path (indices for list elements) -> the override that set it.
  std::map<std::string, std::string> overrides;
  // Block path -> keys that getters asked for, in order. Kept per document so that every
  // ParamBlock over the same map shares it.
  std::map<std::string, std::vector<std::string>> known;
};

struct ParamBlock::State {
  std::shared_ptr<Document> document;
  YAML::Node node;
  std::string path;
  std::vector<std::string>& known() const { return document->known[path]; }
};

namespace {

std::string JoinPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// Bounds on a configuration's tree. yaml-cpp resolves an alias to the anchored node itself,
// so `a: &x [*x]` is a sequence that contains itself, and aliases of aliases ("billion laughs")
// make a small file a tree of millions of values: every walk over the tree would recurse
// without end or run for minutes. A configuration is a few hundred values deep at most.
constexpr int kMaxDepth = 64;
// Bytes in one --set override (the program's arguments are capped at 128 KB by Linux anyway).
constexpr size_t kMaxOverrideBytes = 64u << 10;
constexpr long kMaxValues = 100000;

struct TreeWalk {
  const std::string& source;
  long values = 0;
};

std::string LineOf(const YAML::Node& node, const std::string& source) {
  const YAML::Mark mark = node.Mark();
  // An override's value is one line of its own: the override names it.
  if (mark.is_null() || source.rfind("--set ", 0) == 0) return source;
  return source + ":" + std::to_string(mark.line + 1);
}

// Rejects duplicate keys anywhere in the tree (yaml-cpp would silently keep the first), and
// trees deeper than kMaxDepth (an alias inside the node it names) or of more than kMaxValues
// values once aliases are expanded.
void CheckTree(const YAML::Node& node, int depth, TreeWalk* walk) {
  if (depth > kMaxDepth) {
    throw ConfigError(LineOf(node, walk->source) + ": nested more than " +
                      std::to_string(kMaxDepth) +
                      " levels deep (an alias used inside the node it names?)");
  }
  if (++walk->values > kMaxValues) {
    throw ConfigError(LineOf(node, walk->source) + ": more than " + std::to_string(kMaxValues) +
                      " values, each alias counted where it is used (docs/LIMITS.md): a list "
                      "that long belongs in a data file, and aliases of aliases multiply");
  }
  if (node.IsMap()) {
    std::set<std::string> seen;
    for (auto it = node.begin(); it != node.end(); ++it) {
      if (!it->first.IsScalar()) {
        throw ConfigError(LineOf(it->first, walk->source) + ": a key must be a name, not " +
                          (it->first.IsSequence() ? "a list" : "a map"));
      }
      const std::string key = it->first.Scalar();
      if (!seen.insert(key).second) {
        throw ConfigError(walk->source + ":" + std::to_string(it->first.Mark().line + 1) +
                          ": duplicate key '" + key + "'");
      }
      CheckTree(it->second, depth + 1, walk);
    }
  } else if (node.IsSequence()) {
    for (const YAML::Node& element : node) CheckTree(element, depth + 1, walk);
  }
}

void CheckTree(const YAML::Node& node, const std::string& source) {
  TreeWalk walk{source};
  CheckTree(node, 0, &walk);
}

ParamBlock MakeRoot(const YAML::Node& root, const std::string& source) {
  if (root.IsDefined() && !root.IsNull() && !root.IsMap()) {
    throw ConfigError(source + ":" + std::to_string(root.Mark().line + 1) +
                      ": the top level must be a map of keys");
  }
  CheckTree(root, source);
  auto state = std::make_shared<ParamBlock::State>();
  state->document = std::make_shared<Document>();
  state->document->source = source;
  state->node = (root.IsDefined() && !root.IsNull()) ? root : YAML::Node(YAML::NodeType::Map);
  return ParamBlock(state);
}

std::string Describe(const YAML::Node& node) {
  if (node.IsNull()) return "no value";
  if (node.IsScalar()) return "'" + Abbreviate(node.Scalar()) + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return "nothing";
}

}  // namespace

ParamBlock::ParamBlock() : ParamBlock(MakeRoot(YAML::Node(), "<defaults>")) {}

ParamBlock::ParamBlock(std::shared_ptr<State> state) : state_(std::move(state)) {}

ParamBlock ParamBlock::LoadFile(const std::string& path) {
  return Parse(ReadRegularFile(path, "the YAML file", ExitStatus::kUsage, kMaxConfigBytes), path);
}

ParamBlock ParamBlock::Parse(const std::string& text, const std::string& source) {
  // YAML is UTF-8; yaml-cpp would replace the bad bytes, and a path read here would name
  // another file when written back to a run's config.yaml.
  const size_t bad = InvalidUtf8At(text);
  if (bad != std::string::npos) {
    const long line = std::count(text.begin(), text.begin() + static_cast<long>(bad), '\n') + 1;
    throw ConfigError(source + ":" + std::to_string(line) + ": not valid UTF-8 (byte " +
                      std::to_string(bad) + "); YAML files must be UTF-8");
  }
  const size_t control = NonPrintableAt(text);
  if (control != std::string::npos) {
    const long line = std::count(text.begin(), text.begin() + static_cast<long>(control), '\n') + 1;
    throw ConfigError(source + ":" + std::to_string(line) + ": a control character (byte " +
                      std::to_string(control) + ") that YAML does not allow");
  }
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError(source + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) + ": lists and maps nested " +
                      std::to_string(e.depth()) + " levels deep; a configuration is at most " +
                      std::to_string(kMaxDepth) + " levels deep");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) + ": YAML syntax error: " + e.msg);
  }
  return MakeRoot(root, source);
}

namespace {

// The position of the '=' of `--set KEY.PATH=VALUE`, once the whole assignment is checked: its
// size, its form, UTF-8 without control characters.
size_t CheckedEquals(const std::string& assignment) {
  if (assignment.size() > kMaxOverrideBytes) {
    throw ConfigError("--set " + Abbreviate(assignment, 60) + ": more than " +
                      std::to_string(kMaxOverrideBytes >> 10) + " KB (docs/LIMITS.md); put " +
                      "large values in a configuration file");
  }
  const size_t equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw ConfigError("--set " + Abbreviate(assignment) + ": expected KEY.PATH=VALUE");
  }
  if (InvalidUtf8At(assignment) != std::string::npos) {
    throw ConfigError("--set " + Abbreviate(assignment) + ": not valid UTF-8");
  }
  if (NonPrintableAt(assignment) != std::string::npos) {
    throw ConfigError("--set: a control character that YAML does not allow");
  }
  return equals;
}

}  // namespace

void ParamBlock::Override(const std::string& assignment) {
  ATTEND_CHECK(state_->path.empty()) << "overrides apply to the root block";
  const size_t equals = CheckedEquals(assignment);
  const std::string key_path = assignment.substr(0, equals);
  const std::string value_text = assignment.substr(equals + 1);
  YAML::Node value;
  try {
    value = YAML::Load(value_text);
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError("--set " + Abbreviate(assignment) + ": lists and maps nested " +
                      std::to_string(e.depth()) + " levels deep; at most " +
                      std::to_string(kMaxDepth) + " are read");
  } catch (const YAML::ParserException& e) {
    throw ConfigError("--set " + Abbreviate(assignment) + ": the value is not valid YAML: " + e.msg);
  }
  if (!value.IsDefined()) value = YAML::Node(YAML::NodeType::Null);
  CheckTree(value, "--set " + Abbreviate(assignment));

  const std::vector<std::string> parts = Split(key_path, '.');
  YAML::Node current;
  current.reset(state_->node);
  std::string resolved;  // the path with list elements as indices
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& part = parts[i];
    if (part.empty())
      throw ConfigError("--set " + Abbreviate(assignment) + ": empty key in '" + key_path + "'");
    const bool last = i + 1 == parts.size();
    YAML::Node next;
    if (current.IsSequence()) {
      int index = -1;
      if (std::all_of(part.begin(), part.end(), ::isdigit)) {
        const auto [end, status] = std::from_chars(part.data(), part.data() + part.size(), index);
        if (status != std::errc() || end != part.data() + part.size() ||
            index >= static_cast<int>(current.size())) {
          throw ConfigError("--set " + assignment + ": '" + JoinPath(resolved, part) +
                            "': the list has " + std::to_string(current.size()) + " elements");
        }
      } else {
        std::vector<std::string> names;
        for (size_t k = 0; k < current.size(); ++k) {
          const YAML::Node name = current[k].IsMap() ? current[k]["name"] : YAML::Node();
          if (name.IsDefined() && name.IsScalar()) {
            names.push_back(name.Scalar());
            if (name.Scalar() == part && index < 0) index = static_cast<int>(k);
          }
        }
        if (index < 0) {
          throw ConfigError("--set " + Abbreviate(assignment) + ": '" + resolved + "' has no element named '" +
                            part + "'" + DidYouMean(part, names));
        }
      }
      resolved = JoinPath(resolved, std::to_string(index));
      if (last) {
        current[index] = value;
        break;
      }
      next.reset(current[index]);
    } else {
      if (!current.IsMap()) {
        throw ConfigError("--set " + Abbreviate(assignment) + ": '" + resolved + "' is not a map or a list");
      }
      resolved = JoinPath(resolved, part);
      if (last) {
        current[part] = value;
        break;
      }
      if (!current[part].IsDefined() || current[part].IsNull()) {
        current[part] = YAML::Node(YAML::NodeType::Map);
      }
      next.reset(current[part]);
    }
    current.reset(next);
  }
  state_->document->overrides[resolved] = assignment;
}

const std::string& ParamBlock::path() const { return state_->path; }

const std::string& ParamBlock::source() const { return state_->document->source; }

std::string ParamBlock::KeyPath(const std::string& key) const {
  return key.empty() ? state_->path : JoinPath(state_->path, key);
}

std::string ParamBlock::Where(const std::string& key) const {
  // An override of this key or of any block above it is where the value came from.
  const std::string full = KeyPath(key);
  for (const auto& [path, assignment] : state_->document->overrides) {
    if (full == path || full.rfind(path + ".", 0) == 0) return "--set " + assignment;
  }
  // A check of a whole block may be about values that overrides set inside it: those come
  // first, then where the block is written.
  std::string set_inside;
  if (key.empty()) {
    for (const auto& [path, assignment] : state_->document->overrides) {
      if (full.empty() || path.rfind(full + ".", 0) == 0) {
        set_inside += (set_inside.empty() ? "--set " : ", --set ") + assignment;
      }
    }
  }
  const std::string written = WrittenAt(key);
  return set_inside.empty() ? written : set_inside + " (" + written + ")";
}

std::string ParamBlock::WrittenAt(const std::string& key) const {
  YAML::Mark mark = state_->node.Mark();
  if (!key.empty() && state_->node.IsMap()) {
    for (auto it = state_->node.begin(); it != state_->node.end(); ++it) {
      if (it->first.Scalar() == key) {
        mark = it->first.Mark();
        break;
      }
    }
  }
  if (mark.line < 0) return state_->document->source;
  return state_->document->source + ":" + std::to_string(mark.line + 1);
}

bool ParamBlock::Has(const std::string& key) const {
  const YAML::Node value = state_->node[key];
  return value.IsDefined() && !value.IsNull();
}

std::vector<std::string> ParamBlock::Keys() const {
  std::vector<std::string> keys;
  for (auto it = state_->node.begin(); it != state_->node.end(); ++it) {
    keys.push_back(it->first.Scalar());
  }
  return keys;
}

void ParamBlock::Fail(const std::string& key, const std::string& message) const {
  const std::string path = KeyPath(key);
  throw ConfigError(Where(key) + ": " + (path.empty() ? "" : path + ": ") + message);
}

void ParamBlock::FailCheck(const std::string& error) const {
  const size_t end = error.find_first_of(": ");
  const std::string key = error.substr(0, end);
  if (end == std::string::npos || !Has(key)) Fail("", error);
  const size_t rest = error.find_first_not_of(": ", end);
  Fail(key, rest == std::string::npos ? error : error.substr(rest));
}

namespace {

// Records `key` as known and returns its node (undefined or null when absent).
YAML::Node Lookup(const ParamBlock::State& state, const std::string& key) {
  std::vector<std::string>& known = state.known();
  if (std::find(known.begin(), known.end(), key) == known.end()) known.push_back(key);
  if (!state.node.IsMap()) return YAML::Node();
  return state.node[key];
}

bool Absent(const YAML::Node& node) { return !node.IsDefined(); }

template <typename T>
bool DecodeScalar(const YAML::Node& node, T* value) {
  if (!node.IsScalar()) return false;
  return YAML::convert<T>::decode(node, *value);
}

}  // namespace

bool ParamBlock::GetBool(const std::string& key, bool default_value) const {
  const YAML::Node node = Lookup(*state_, key);
  if (Absent(node)) return default_value;
  bool value = false;
  if (!DecodeScalar(node, &value)) Fail(key, "expected true or false, got " + Describe(node));
  return value;
}

int ParamBlock::GetInt(const std::string& key, int default_value, Range range) const {
  const YAML::Node node = Lookup(*state_, key);
  if (Absent(node)) return default_value;
  int value = 0;
  if (!DecodeScalar(node, &value)) Fail(key, "expected an integer, got " + Describe(node));
  if (!range.Contains(value))
    Fail(key, "value " + Abbreviate(node.Scalar()) + " out of range: " + range.Describe());
  return value;
}

double ParamBlock::GetDouble(const std::string& key, double default_value, Range range) const {
  const YAML::Node node = Lookup(*state_, key);
  if (Absent(node)) return default_value;
  double value = 0.0;
  if (!DecodeScalar(node, &value)) Fail(key, "expected a number, got " + Describe(node));
  // YAML spells infinity .inf and not-a-number .nan; no key takes either, whatever its range.
  if (!std::isfinite(value)) Fail(key, "value " + node.Scalar() + " is not a finite number");
  if (!range.Contains(value))
    Fail(key, "value " + Abbreviate(node.Scalar()) + " out of range: " + range.Describe());
  return value;
}

std::string ParamBlock::GetString(const std::string& key, const std::string& default_value) const {
  const YAML::Node node = Lookup(*state_, key);
  if (Absent(node)) return default_value;
  if (!node.IsScalar()) Fail(key, "expected a string, got " + Describe(node));
  return node.Scalar();
}

std::string ParamBlock::GetChoice(const std::string& key, const std::string& default_value,
                                  const std::vector<std::string>& choices) const {
  const std::string value = GetString(key, default_value);
  if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
    Fail(key, "'" + value + "' is not one of " + Join(choices, ", ") + DidYouMean(value, choices));
  }
  return value;
}

namespace {

template <typename T>
std::vector<T> GetList(const ParamBlock& block, const std::string& key,
                       const std::vector<T>& default_value, const char* what, const Range* range,
                       int size) {
  const YAML::Node node = Lookup(*block.state(), key);
  if (Absent(node)) return default_value;
  if (!node.IsSequence()) {
    block.Fail(key, std::string("expected a list of ") + what + ", got " + Describe(node));
  }
  std::vector<T> values;
  for (size_t i = 0; i < node.size(); ++i) {
    T value{};
    if (!DecodeScalar(node[i], &value)) {
      block.Fail(key, "element " + std::to_string(i) + ": expected " + what + ", got " +
                          Describe(node[i]));
    }
    if constexpr (std::is_floating_point_v<T>) {
      if (!std::isfinite(value)) {
        block.Fail(key, "element " + std::to_string(i) + " = " + Abbreviate(node[i].Scalar()) +
                            " is not a finite number");
      }
    }
    if constexpr (std::is_arithmetic_v<T>) {
      if (range != nullptr && !range->Contains(static_cast<double>(value))) {
        block.Fail(key, "element " + std::to_string(i) + " = " + Abbreviate(node[i].Scalar()) +
                            " out of range: " + range->Describe());
      }
    }
    values.push_back(value);
  }
  if (size >= 0 && static_cast<int>(values.size()) != size) {
    block.Fail(key, "expected " + std::to_string(size) + " elements, got " +
                        std::to_string(values.size()));
  }
  return values;
}

}  // namespace

std::vector<double> ParamBlock::GetDoubles(const std::string& key,
                                           const std::vector<double>& default_value, Range range,
                                           int size) const {
  return GetList(*this, key, default_value, "numbers", &range, size);
}

std::vector<int> ParamBlock::GetInts(const std::string& key, const std::vector<int>& default_value,
                                     Range range, int size) const {
  return GetList(*this, key, default_value, "integers", &range, size);
}

std::vector<std::string> ParamBlock::GetStrings(
    const std::string& key, const std::vector<std::string>& default_value) const {
  return GetList<std::string>(*this, key, default_value, "strings", nullptr, -1);
}

std::uint64_t ParamBlock::GetCount(const std::string& key, std::uint64_t default_value,
                                   std::uint64_t max) const {
  const YAML::Node node = Lookup(*state_, key);
  if (Absent(node)) return default_value;
  // Read as text: yaml-cpp's integers stop at 64 bits signed, and a seed may use all 64.
  const std::string text = node.IsScalar() ? node.Scalar() : "";
  std::uint64_t value = 0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (!node.IsScalar() || status != std::errc() || end != text.data() + text.size() ||
      value > max) {
    Fail(key, "expected an integer in [0, " + std::to_string(max) + "], got " +
                  (node.IsScalar() ? "'" + Abbreviate(text) + "'" : Describe(node)));
  }
  return value;
}

double ParamBlock::RequireDouble(const std::string& key, Range range) const {
  if (!Has(key)) {
    Lookup(*state_, key);
    Fail(key, "required key is missing");
  }
  return GetDouble(key, 0.0, range);
}

std::string ParamBlock::RequireString(const std::string& key) const {
  if (!Has(key)) {
    Lookup(*state_, key);
    Fail(key, "required key is missing");
  }
  return GetString(key, "");
}

ParamBlock ParamBlock::Child(const std::string& key) const {
  const YAML::Node node = Lookup(*state_, key);
  auto child = std::make_shared<State>();
  child->document = state_->document;
  child->path = KeyPath(key);
  if (Absent(node) || node.IsNull()) {
    child->node = YAML::Node(YAML::NodeType::Map);
  } else if (!node.IsMap()) {
    Fail(key, "expected a map of keys, got " + Describe(node));
  } else {
    child->node = node;
  }
  return ParamBlock(child);
}

std::vector<ParamBlock> ParamBlock::Children(const std::string& key) const {
  const YAML::Node node = Lookup(*state_, key);
  std::vector<ParamBlock> children;
  if (Absent(node) || node.IsNull()) return children;
  if (!node.IsSequence()) Fail(key, "expected a list, got " + Describe(node));
  for (size_t i = 0; i < node.size(); ++i) {
    auto child = std::make_shared<State>();
    child->document = state_->document;
    child->path = KeyPath(key) + "." + std::to_string(i);
    if (!node[i].IsMap()) {
      ParamBlock element(child);
      element.state_->node = node[i];
      element.Fail("", "expected a map of keys, got " + Describe(node[i]));
    }
    child->node = node[i];
    children.emplace_back(child);
  }
  return children;
}

namespace {

std::string FlowTextOf(const YAML::Node& node) {
  YAML::Emitter out;
  out << YAML::Flow << node;
  return out.c_str();
}

}  // namespace

ParamBlock::Text ParamBlock::ValueText(const std::string& key) const {
  const YAML::Node node = Lookup(*state_, key);
  if (Absent(node)) Fail(key, "required key is missing");
  return {FlowTextOf(node), Where(key)};
}

std::vector<ParamBlock::Text> ParamBlock::ElementTexts(const std::string& key) const {
  const YAML::Node node = Lookup(*state_, key);
  std::vector<Text> texts;
  if (Absent(node) || node.IsNull()) return texts;
  if (!node.IsSequence()) Fail(key, "expected a list, got " + Describe(node));
  const std::string overridden = Where(key);
  for (const YAML::Node& element : node) {
    // An element set by --set is reported there; one in the file at its own line.
    const bool from_file = overridden.rfind("--set ", 0) != 0 && !element.Mark().is_null();
    texts.push_back({FlowTextOf(element),
                     from_file ? state_->document->source + ":" +
                                     std::to_string(element.Mark().line + 1)
                               : overridden});
  }
  return texts;
}

bool ParamBlock::IsList(const std::string& key) const {
  return state_->node.IsMap() && state_->node[key].IsSequence();
}

bool ParamBlock::IsMap(const std::string& key) const {
  return state_->node.IsMap() && state_->node[key].IsMap();
}

void ParamBlock::CheckNoUnknownKeys() const {
  const std::vector<std::string>& known = state_->known();
  for (const std::string& key : Keys()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      const std::string where = state_->path.empty() ? "" : " in " + state_->path;
      throw ConfigError(Where(key) + ": unknown key '" + key + "'" + where +
                        DidYouMean(key, known));
    }
  }
}

void ParamBlock::Accept(const std::string& key) const { Lookup(*state_, key); }

std::vector<std::string> ParamBlock::KnownKeys() const { return state_->known(); }

YAML::Node NodeOf(const ParamBlock& block) { return block.state()->node; }

}  // namespace attend
