#include "io/source_spec.h"

namespace attend {

const OptionFields<SourceSpec>& SourceSpec::Fields() {
  using S = SourceSpec;
  static const OptionFields<SourceSpec> fields = {
      {"folder", &S::folder,
       "sequence folder with left/ and right/ (or left/ alone), or a KITTI raw drive or "
       "tracking training/image_02/NNNN (docs/SEQUENCES.md)"},
      {"left_video", &S::left_video, "left video of a stereo pair (with right_video)"},
      {"right_video", &S::right_video, "right video of a stereo pair"},
      {"side_by_side_video", &S::side_by_side_video, "one video, the left view in its left half"},
      {"video", &S::video, "a monocular video"},
      {"images", &S::images, "a plain folder of frames, monocular, in sorted name order"},
      {"camera", &S::camera, Range::Closed(-1, 4095), "a live V4L2 camera /dev/videoN; -1: none"},
      {"camera_right", &S::camera_right, Range::Closed(-1, 4095),
       "the right camera of a live stereo pair; -1: none"},
      {"gst", &S::gst, "a live GStreamer pipeline (ending in an appsink)"},
      {"gst_right", &S::gst_right, "the right pipeline of a live stereo pair"},
      {"calib", &S::calib,
       "the stereo calibration (calib.yaml, docs/STEREO3D.md); wins over SEQ/calib.yaml"}};
  return fields;
}

int SourceSpec::SourceCount() const {
  const bool has_pair = !left_video.empty() || !right_video.empty();
  return (folder.empty() ? 0 : 1) + (has_pair ? 1 : 0) + (side_by_side_video.empty() ? 0 : 1) +
         (video.empty() ? 0 : 1) + (images.empty() ? 0 : 1) + (IsLive() ? 1 : 0);
}

bool SourceSpec::IsLive() const {
  return camera >= 0 || camera_right >= 0 || !gst.empty() || !gst_right.empty();
}

SourceKind SourceSpec::Kind() const {
  if (!folder.empty()) return SourceKind::kFolder;
  if (!left_video.empty() || !right_video.empty()) return SourceKind::kVideoPair;
  if (!side_by_side_video.empty()) return SourceKind::kSideBySide;
  if (!video.empty()) return SourceKind::kVideo;
  if (!images.empty()) return SourceKind::kImages;
  if (IsLive()) return SourceKind::kLive;
  return SourceKind::kNone;
}

std::vector<std::string*> SourceSpec::Paths() {
  return {&folder, &left_video, &right_video, &side_by_side_video, &video, &images, &calib};
}

std::string SourceSpec::Check() const {
  const std::string error = CheckKinds();
  return error.empty() ? CheckLive() : error;
}

std::string SourceSpec::CheckKinds() const {
  const bool has_pair = !left_video.empty() || !right_video.empty();
  const int sources = SourceCount();
  // No source is valid here: `attend run` then takes the bundled sequence. Opening needs one.
  if (sources > 1) {
    return "at most one source may be set (folder, left_video + right_video, "
           "side_by_side_video, video, images, or a live camera or gst), got " +
           std::to_string(sources);
  }
  if (has_pair && (left_video.empty() || right_video.empty())) {
    return left_video.empty() ? "left_video must be set together with right_video"
                              : "right_video must be set together with left_video";
  }
  return CheckFieldRanges(*this, Fields());
}

std::string SourceSpec::CheckLive() const {
  const std::string ranges = CheckFieldRanges(live, LiveOptions::Fields());
  if (!ranges.empty()) return "live." + ranges;
  const LiveView left = LeftView(*this);
  const LiveView right = RightView(*this);
  if (camera >= 0 && !gst.empty()) {
    return "camera and gst are both set; a live view is one camera or one pipeline";
  }
  if (camera_right >= 0 && !gst_right.empty()) {
    return "camera_right and gst_right are both set; a live view is one camera or one pipeline";
  }
  if (!right.empty() && left.empty()) {
    return std::string(camera_right >= 0 ? "camera_right" : "gst_right") +
           " needs camera or gst for the left view";
  }
  if (camera >= 0 && camera == camera_right) {
    return "camera and camera_right are the same device " + std::to_string(camera);
  }
  if (live.side_by_side && left.empty()) {
    return "live.side_by_side needs a live source (camera or gst)";
  }
  if (live.side_by_side && !right.empty()) {
    return "live.side_by_side reads both views from one source, so camera_right and gst_right "
           "must not be set";
  }
  if (live.duration_s > 0 && !IsLive()) {
    return "live.duration_s bounds a live source (camera or gst) only";
  }
  return "";
}

std::string SourceSpec::Describe() const {
  switch (Kind()) {
    case SourceKind::kFolder:
      return "folder " + folder;
    case SourceKind::kVideoPair:
      return "videos " + left_video + " + " + right_video;
    case SourceKind::kSideBySide:
      return "side-by-side video " + side_by_side_video;
    case SourceKind::kVideo:
      return "video " + video;
    case SourceKind::kImages:
      return "images " + images;
    case SourceKind::kLive: {
      const LiveView left = LeftView(*this);
      const LiveView right = RightView(*this);
      if (live.side_by_side) return "side-by-side " + left.Describe();
      if (right.empty()) return left.Describe();
      if (left.empty()) return "(no left view) + " + right.Describe();
      return left.Describe() + " + " + right.Describe();
    }
    case SourceKind::kNone:
      break;
  }
  return "no source";
}

std::string LiveView::Describe() const {
  if (camera >= 0) return "camera " + std::to_string(camera);
  return "GStreamer pipeline '" + gst + "'";
}

std::string LiveView::FrameStem() const {
  return camera >= 0 ? "/dev/video" + std::to_string(camera) : key;
}

std::string LiveView::Name() const {
  return camera >= 0 ? "camera" + std::to_string(camera) : "gst";
}

LiveView LeftView(const SourceSpec& spec) { return {spec.camera, spec.gst, "gst"}; }

LiveView RightView(const SourceSpec& spec) {
  return {spec.camera_right, spec.gst_right, "gst_right"};
}

bool LiveIsStereo(const SourceSpec& spec) {
  return !RightView(spec).empty() || spec.live.side_by_side;
}

}  // namespace attend
