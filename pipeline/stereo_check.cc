#include "pipeline/stereo_check.h"

#include <optional>
#include <sstream>
#include <utility>

#include "stereo/row_check.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

// A source whose first frame was read ahead of the run: hands it out first, then the rest.
class FirstFrameKept final : public FrameSource {
 public:
  FirstFrameKept(std::unique_ptr<FrameSource> source, StereoFrame first)
      : source_(std::move(source)), first_(std::move(first)) {}

  const SequenceInfo& info() const override { return source_->info(); }
  bool Next(StereoFrame* frame) override {
    if (first_.has_value()) {
      *frame = std::move(*first_);
      first_.reset();
      return true;
    }
    return source_->Next(frame);
  }
  void WatchStop(const std::atomic<bool>* stop) override { source_->WatchStop(stop); }
  std::optional<LiveStatus> live_status() const override { return source_->live_status(); }

 private:
  std::unique_ptr<FrameSource> source_;
  std::optional<StereoFrame> first_;
};

std::string RowsProblem(const StereoFrame& frame, const SequenceInfo& info,
                        const StereoSummary& summary) {
  std::ostringstream out;
  out << "frame " << frame.index << " (" << frame.left_path << ", " << frame.right_path
      << "): the views' rows do not match: the same points are " << Fixed(summary.row_offset_px, 2)
      << " px apart in rows (median over " << summary.matches << " matched features; a rectified "
      << "pair measures under " << Fixed(kMaxRowOffsetPx, 1) << " px)";
  if (info.calibration == nullptr) {
    out << ". The pair is not rectified: calibrate the camera (attend calibrate) and give the "
           "calibration with --calib FILE or as SEQ/calib.yaml, so that attend rectifies it";
  } else if (info.calibration->rectifies()) {
    out << ", rectified with " << info.calibration->source
        << ": the calibration does not fit this camera; calibrate it again (attend calibrate)";
  } else {
    out << ". The calibration (" << info.calibration->source
        << ") says the pair is rectified, but it is not: give a full calibration (attend "
           "calibrate) with --calib FILE or as SEQ/calib.yaml";
  }
  out << "; sequence.check_rows: false turns the check off";
  return out.str();
}

}  // namespace

std::string CalibrationFormName(StereoCalibration::Form form) {
  switch (form) {
    case StereoCalibration::Form::kFull:
      return "full";
    case StereoCalibration::Form::kRectified:
      return "rectified";
    case StereoCalibration::Form::kNominal:
      return "nominal";
  }
  return "";
}

std::optional<StereoSummary> CheckStereoSource(bool check_rows,
                                               std::unique_ptr<FrameSource>* source) {
  const SequenceInfo& info = (*source)->info();
  if (!info.stereo) return std::nullopt;
  std::optional<StereoSummary> summary(std::in_place);
  if (info.calibration != nullptr) {
    summary->calibration_form = CalibrationFormName(info.calibration->form);
    summary->calibration_source = info.calibration->source;
    summary->rectified_on_the_fly = info.calibration->rectifies();
  }
  if (!check_rows) {
    summary->note = "sequence.check_rows is off";
    return summary;
  }
  StereoFrame first;
  if (!(*source)->Next(&first)) {
    summary->note = "no frame to check";
    return summary;
  }
  const RowCheck check = MeasureRowOffset(first.left, first.right);
  summary->row_checked = true;
  summary->frame = first.index;
  summary->matches = check.matches;
  summary->row_offset_px = check.row_offset_px / info.scale_y;
  const bool bad = check.Decided() && summary->row_offset_px > kMaxRowOffsetPx;
  if (bad) throw InputError(RowsProblem(first, info, *summary));
  if (!check.Decided()) {
    summary->note = "too few features matched (" + std::to_string(check.matches) + " of " +
                    std::to_string(kMinRowMatches) + ") for a verdict on the rows";
  }
  *source = std::make_unique<FirstFrameKept>(std::move(*source), std::move(first));
  return summary;
}

nlohmann::ordered_json StereoSummaryJson(const StereoSummary& s) {
  using json = nlohmann::ordered_json;
  json calibration = nullptr;
  if (!s.calibration_form.empty()) {
    calibration = {{"form", s.calibration_form}, {"source", s.calibration_source}};
  }
  return {{"calibration", calibration},
          {"rectified_on_the_fly", s.rectified_on_the_fly},
          {"row_check", s.row_checked},
          {"row_check_frame", s.row_checked ? json(s.frame) : json()},
          {"row_offset_px", s.row_checked ? json(s.row_offset_px) : json()},
          {"matches", s.matches},
          {"note", s.note.empty() ? json() : json(s.note)}};
}

}  // namespace attend
