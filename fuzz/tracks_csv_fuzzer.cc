// tracks.csv, written by `attend track` and read by `attend eval-tracking` (docs/TRACKING.md):
// the input is the file, read with ReadTracksCsv. Rows that read must round-trip exactly
// through WriteTracksCsv, as its header promises, and are then scored as the program scores
// them: `attend eval-tracking INPUT --gt GT` against a fixed OTB box list of six frames.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/cli_support.h"
#include "fuzz/fuzz_support.h"
#include "io/tracking_files.h"

namespace {

// A fixed OTB box list of six frames, written at initialisation.
std::string ground_truth_path;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  attend::fuzz::SilenceStandardOutput();
  ground_truth_path = attend::fuzz::ScratchFile(
      "groundtruth_rect.txt",
      "41,61,30,24\n42,61,30,24\n43,62,30,24\n0,0,0,0\n45,63,31,24\n101,11,12,12\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("tracks.csv");
  static const std::string copy = fuzz::ScratchPath("copy.csv");
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const std::vector<TrackRow> rows = ReadTracksCsv(input);
    WriteTracksCsv(copy, rows);
    const std::vector<TrackRow> again = ReadTracksCsv(copy);
    if (again.size() != rows.size()) fuzz::Fail("tracks.csv loses rows in a round trip");
    for (size_t i = 0; i < rows.size(); ++i) {
      const TrackRow& a = rows[i];
      const TrackRow& b = again[i];
      if (a.frame != b.frame || a.id != b.id || a.box != b.box || a.state != b.state) {
        fuzz::Fail("tracks.csv row " + std::to_string(i) + " changes in a round trip");
      }
    }
    fuzz::RunCommand({"eval-tracking", input, "--gt", ground_truth_path});
  });
  return 0;
}
