// The `--set KEY.PATH=VALUE` overrides of `attend run` on top of configs/default.yaml, applied
// as LoadOptions applies them: ParamBlock::Override for each, in order, then ReadOptions. Each
// non-empty line of the input is one override (the value is YAML, so a line may hold a flow
// list or map).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "config/param_block.h"
#include "fuzz/fuzz_support.h"
#include "pipeline/options_io.h"

namespace {

// More overrides than a command line holds add nothing but time.
constexpr size_t kMaxOverrides = 64;

const std::string& DefaultPath() {
  static const std::string path = std::string(ATTEND_FUZZ_SOURCE_ROOT) + "/configs/default.yaml";
  return path;
}

const std::string& DefaultText() {
  static const std::string text = attend::fuzz::ReadFile(DefaultPath());
  return text;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  DefaultText();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  std::vector<std::string> overrides;
  const std::string text = fuzz::ToString(data, size);
  size_t begin = 0;
  while (begin <= text.size() && overrides.size() < kMaxOverrides) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    if (end > begin) overrides.push_back(text.substr(begin, end - begin));
    begin = end + 1;
  }
  fuzz::ExpectOnlyDocumentedErrors([&] {
    // Parsed afresh each time: Override changes the document in place.
    ParamBlock root = ParamBlock::Parse(DefaultText(), DefaultPath());
    for (const std::string& assignment : overrides) root.Override(assignment);
    ReadOptions(root);
  });
  return 0;
}
