// DisparityOptions (stereo/disparity.h): its field table and its check.
#include <string>

#include "stereo/disparity.h"
#include "util/enum_table.h"

namespace attend {

namespace {

constexpr EnumTable<DisparitySmoothness, 3> kSmoothness = {{{
    {DisparitySmoothness::kHard, "hard"},
    {DisparitySmoothness::kPenalty, "penalty"},
    {DisparitySmoothness::kSgm, "sgm"},
}}};

}  // namespace

const char* DisparitySmoothnessName(DisparitySmoothness smoothness) {
  return kSmoothness.Name(smoothness);
}

const OptionFields<DisparityOptions>& DisparityOptions::Fields() {
  using O = DisparityOptions;
  static const OptionFields<DisparityOptions> fields = {
      {"max_disparity", &O::max_disparity, Range::Closed(1, kMaxDisparity),
       "D: disparities 0..D-1 are searched; below the image width"},
      {"window", &O::window, Range::Closed(1, 31), "side of the square ZNCC window, odd"},
      {"subpixel", &O::subpixel, "parabola through the correlation peak: fractions of a pixel"},
      {"left_right_check", &O::left_right_check,
       "left-right consistency check, then fill from the farther valid neighbour"},
      {"lr_tolerance", &O::lr_tolerance, Range::AtLeast(0), "the check's tolerance, px"},
      {"smoothness", EnumField<&O::smoothness, kSmoothness>(),
       "hard: the thesis's |d(x) - d(x-1)| <= 1; penalty: jumps at jump_penalty; sgm: "
       "semi-global matching along sgm_paths paths"},
      {"jump_penalty", &O::jump_penalty, Range::AtLeast(0),
       "penalty: the cost of a jump, ZNCC units"},
      {"sgm_p1", &O::sgm_p1, Range::Closed(0, 16),
       "sgm: the cost of a step of one disparity, ZNCC units"},
      {"sgm_p2", &O::sgm_p2, Range::Closed(0, 16),
       "sgm: the cost of a larger jump, ZNCC units; at least sgm_p1"},
      {"median", &O::median, Range::Closed(0, 5),
       "a median filter of this size over the map (0: none; 3 or 5)"},
      {"sgm_paths", &O::sgm_paths, Range::Closed(5, 8),
       "sgm: 8 paths (two passes, the volume kept) or 5 (one pass, as OpenCV's SGBM)"},
      {"max_width", &O::max_width, Range::Closed(0, 1 << 16),
       "wider pairs are halved until they fit, D with them; 0: full size"}};
  return fields;
}

std::string DisparityOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (window % 2 == 0) return "window must be odd";
  if (sgm_p2 < sgm_p1) return "sgm_p2 must be at least sgm_p1";
  if (sgm_paths != 5 && sgm_paths != 8) return "sgm_paths must be 5 or 8";
  if (median != 0 && median != 3 && median != 5) return "median must be 0, 3 or 5";
  return "";
}
}  // namespace attend
