// RUN/frames.jsonl, one frame record a line (SPEC 3.3): the input is the file, read with
// ReadFrameRecords, then scored as `attend eval` scores it (EvaluateAttention against the
// ground truth of run_folder_support.h) and summarised as `attend compare` summarises it
// (SummariseTargets, TargetsToJson).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "fuzz/run_folder_support.h"
#include "eval/run_comparison.h"
#include "eval/run_evaluation.h"
#include "util/json_text.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("frames.jsonl");
  static const std::vector<GtObject> truth = fuzz::ValidObjects();
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const std::vector<FrameRecord> frames = ReadFrameRecords(input);
    const AttentionScores scores = EvaluateAttention(frames, truth);
    JsonText(AttentionToJson(scores));
    JsonText(TargetsToJson(SummariseTargets(frames)));
  });
  return 0;
}
