// gt/objects.csv, the ground truth of a sequence (SPEC 3.1): the input is the file, read with
// ReadObjectsCsv. Objects that read must round-trip exactly through WriteObjectsCsv, as its
// header promises, and are then scored as `attend eval` scores a run against them
// (EvaluateAttention, over the frames of run_folder_support.h) and as the program scores a
// track against them: `attend eval-tracking TRACKS --gt INPUT --gt-id 1` with a fixed
// tracks.csv of target 1 over three frames.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/cli_support.h"
#include "fuzz/fuzz_support.h"
#include "fuzz/run_folder_support.h"
#include "io/ground_truth.h"
#include "eval/run_evaluation.h"

namespace {

// Equal field by field; two NaNs would count as equal, though the reader refuses them.
bool Same(double a, double b) { return a == b || (a != a && b != b); }

bool Same(const attend::GtObject& a, const attend::GtObject& b) {
  return a.frame == b.frame && a.id == b.id && Same(a.box.x, b.box.x) && Same(a.box.y, b.box.y) &&
         Same(a.box.width, b.box.width) && Same(a.box.height, b.box.height) &&
         Same(a.visible_fraction, b.visible_fraction) &&
         a.disparity.has_value() == b.disparity.has_value() &&
         (!a.disparity || Same(*a.disparity, *b.disparity)) && a.kind == b.kind;
}

// A fixed tracks.csv of target 1 over three frames, written at initialisation.
std::string tracks_path;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  attend::fuzz::SilenceStandardOutput();
  tracks_path = attend::fuzz::ScratchFile(
      "tracks.csv",
      "frame,id,x,y,w,h,state\n0,1,4,4,10,8,found\n1,1,5,4,10,8,found\n2,1,6,4,10,8,occluded\n");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("objects.csv");
  static const std::string copy = fuzz::ScratchPath("copy.csv");
  static const std::vector<FrameRecord> frames = fuzz::ValidFrames();
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const std::vector<GtObject> objects = ReadObjectsCsv(input);
    WriteObjectsCsv(copy, objects);
    const std::vector<GtObject> again = ReadObjectsCsv(copy);
    if (again.size() != objects.size()) fuzz::Fail("objects.csv loses rows in a round trip");
    for (size_t i = 0; i < objects.size(); ++i) {
      if (!Same(objects[i], again[i])) {
        fuzz::Fail("objects.csv row " + std::to_string(i) + " changes in a round trip");
      }
    }
    EvaluateAttention(frames, objects);
    fuzz::RunCommand({"eval-tracking", tracks_path, "--gt", input, "--gt-id", "1"});
  });
  return 0;
}
