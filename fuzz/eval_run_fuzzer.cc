// The run folder read by `attend eval RUN --gt GT`: the input is one file of a temporary run
// folder (run_folder_support.h: its first byte picks frames.jsonl, summary.json or config.yaml),
// the others and the ground truth stay valid, and the command runs as the program runs it
// (its CLI11 declaration and action from cli/, the JSON report sent nowhere).
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/cli_support.h"
#include "fuzz/fuzz_support.h"
#include "fuzz/run_folder_support.h"

namespace {

struct Fixture {
  std::string run = attend::fuzz::ScratchPath("run");
  std::string sequence = attend::fuzz::ScratchPath("seq");
  attend::fuzz::RunFiles valid = attend::fuzz::ValidRunFiles(sequence);
};

// The valid run folder and ground truth, written at initialisation.
const Fixture* fixture = nullptr;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  static const Fixture written;
  attend::fuzz::WriteGroundTruth(written.sequence);
  attend::fuzz::WriteRunFolder(written.run, written.valid);
  fixture = &written;
  attend::fuzz::SilenceStandardOutput();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  fuzz::WriteFuzzedRunFiles(data, size, fixture->valid, fixture->run);
  fuzz::ExpectOnlyDocumentedErrors([&] {
    fuzz::RunCommand({"eval", fixture->run, "--gt", fixture->sequence + "/gt"});
  });
  return 0;
}
