// The YAML configuration of `attend run` (and of every command that takes --config): the input
// is a configuration file, read as LoadOptions reads one, in memory (ParamBlock::Parse, then
// ReadOptions). A configuration that reads must also survive the round trip OptionsToYaml
// promises: its effective configuration reads back, to the same effective configuration and
// the same file names.
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>

#include "config/param_block.h"
#include "fuzz/fuzz_support.h"
#include "pipeline/options_io.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  const std::string text = fuzz::ToString(data, size);
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const AttendOptions options = ReadOptions(ParamBlock::Parse(text, "fuzz.yaml"));
    const std::string effective = OptionsToYaml(options);
    AttendOptions read_back;
    try {
      read_back = ReadOptions(ParamBlock::Parse(effective, "effective.yaml"));
    } catch (const Error& e) {
      fuzz::Fail(std::string("the effective configuration does not read back: ") + e.what() +
                 "\n" + effective);
    }
    const std::string again = OptionsToYaml(read_back);
    if (again != effective) {
      fuzz::Fail("the effective configuration changes when read back:\n" + effective +
                 "\nbecomes\n" + again);
    }
    // The strings the writer may re-encode: file names must come back byte for byte, or a
    // run's config.yaml names another file than the one the run read.
    const std::pair<const char*, std::pair<const std::string*, const std::string*>> paths[] = {
        {"sequence.folder", {&options.sequence.source.folder, &read_back.sequence.source.folder}},
        {"sequence.left_video", {&options.sequence.source.left_video, &read_back.sequence.source.left_video}},
        {"sequence.right_video", {&options.sequence.source.right_video, &read_back.sequence.source.right_video}},
        {"sequence.side_by_side_video",
         {&options.sequence.source.side_by_side_video, &read_back.sequence.source.side_by_side_video}},
        {"sequence.video", {&options.sequence.source.video, &read_back.sequence.source.video}},
        {"sequence.images", {&options.sequence.source.images, &read_back.sequence.source.images}},
        {"output.dir", {&options.output.dir, &read_back.output.dir}},
        {"select.skin_model", {&options.attention.skin_model, &read_back.attention.skin_model}}};
    for (const auto& [key, values] : paths) {
      if (*values.first != *values.second) {
        fuzz::Fail(std::string(key) + " changes through the effective configuration: '" +
                   *values.first + "' becomes '" + *values.second + "'");
      }
    }
    if (options.plugins != read_back.plugins) {
      fuzz::Fail("plugins change through the effective configuration");
    }
  });
  return 0;
}
