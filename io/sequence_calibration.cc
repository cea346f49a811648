#include "io/sequence_calibration.h"

#include <filesystem>
#include <string>
#include <utility>

#include "util/error.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

std::string SizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// The calibration file of the source: sequence.calib, else SEQ/calib.yaml; "" for none.
std::string CalibrationFile(const SequenceOptions& options, const SequenceInfo& info) {
  if (!options.source.calib.empty()) return options.source.calib;
  if (info.folder.empty()) return "";
  const fs::path beside = fs::path(info.folder) / "calib.yaml";
  std::error_code error;
  return fs::exists(beside, error) ? beside.string() : "";
}

}  // namespace

std::shared_ptr<const Rectifier> AttachCalibration(const SequenceOptions& options,
                                                   SequenceInfo* info) {
  // A calibration the reader found with the frames (a KITTI layout's own, io/kitti_source.h)
  // stands unless sequence.calib names a file; it is checked against the frames as a file is.
  std::shared_ptr<const StereoCalibration> found = std::move(info->calibration);
  info->calibration.reset();
  if (!info->stereo) {
    if (!options.source.calib.empty()) {
      throw ConfigError("sequence.calib (--calib " + options.source.calib +
                        ") is a stereo calibration, but the source (" +
                        options.source.Describe() + ") is monocular");
    }
    return nullptr;
  }
  const std::string file = found != nullptr && options.source.calib.empty()
                               ? found->source
                               : CalibrationFile(options, *info);
  if (file.empty()) {
    if (info->focal_px > 0 && info->baseline_m > 0) {
      info->calibration = std::make_shared<const StereoCalibration>(NominalCalibration(
          info->focal_px, info->baseline_m, info->native_size,
          (fs::path(info->folder) / "sequence.yaml").string() + " (focal_px, baseline_m)"));
    }
    return nullptr;
  }
  auto calibration = found != nullptr && options.source.calib.empty()
                         ? found
                         : std::make_shared<const StereoCalibration>(ReadStereoCalibration(file));
  if (calibration->image_size != info->native_size) {
    throw InputError(file + ": the calibration is for " + SizeText(calibration->image_size) +
                     " frames, but the frames of " + options.source.Describe() + " are " +
                     SizeText(info->native_size) +
                     " (calibrate at the size the camera records; attend scales it to the "
                     "working size itself)");
  }
  info->calibration = calibration;
  if (!calibration->rectifies()) return nullptr;
  return std::make_shared<const Rectifier>(*calibration);
}

}  // namespace attend
