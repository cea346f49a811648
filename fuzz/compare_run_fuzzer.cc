// The run folders read by `attend compare A B` (and `attend report`): the input is one file of
// run B (run_folder_support.h: its first byte picks frames.jsonl, summary.json or config.yaml),
// the rest of B and all of run A stay valid. Both runs are loaded (LoadRun), compared both ways
// (CompareRuns) and written as compare writes them: the JSON and the HTML report, in memory.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "fuzz/run_folder_support.h"
#include "eval/run_comparison.h"
#include "eval/run_report.h"
#include "util/json_text.h"

namespace {

struct Fixture {
  std::string sequence = attend::fuzz::ScratchPath("seq");
  std::string run_a = attend::fuzz::ScratchPath("run_a");
  std::string run_b = attend::fuzz::ScratchPath("run_b");
  attend::fuzz::RunFiles valid = attend::fuzz::ValidRunFiles(sequence);
  attend::RunData a;
};

const Fixture& GetFixture() {
  static const Fixture fixture = [] {
    Fixture f;
    attend::fuzz::WriteGroundTruth(f.sequence);
    attend::fuzz::WriteRunFolder(f.run_a, f.valid);
    attend::fuzz::WriteRunFolder(f.run_b, f.valid);
    f.a = attend::LoadRun(f.run_a);
    return f;
  }();
  return fixture;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  GetFixture();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  const Fixture& fixture = GetFixture();
  fuzz::WriteFuzzedRunFiles(data, size, fixture.valid, fixture.run_b);
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const RunData b = LoadRun(fixture.run_b);
    const RunComparison forward = CompareRuns(fixture.a, b);
    const RunComparison backward = CompareRuns(b, fixture.a);
    JsonText(ComparisonToJson(forward));
    JsonText(ComparisonToJson(backward));
    JsonText(TargetsToJson(SummariseTargets(b.frames)));
    JsonText(AttentionToJson(b.attention));
    ReportInput report;
    report.runs = {fixture.a, b};
    report.comparisons = {forward};
    report.command_line = "attend compare A B";
    ReportHtml(report);
  });
  return 0;
}
