// The stereo calibration file (io/stereo_calibration.h): its forms, its errors, the
// rectification of a raw pair, and where a sequence takes its calibration from
// (io/sequence_calibration.h).
#include "io/stereo_calibration.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/sequence.h"
#include "tests/support/error_message.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/stereo_pair_maker.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::InputErrorOf;
using testing::TempDir;

double MaxDifference(const cv::Mat& a, const cv::Mat& b) { return cv::norm(a, b, cv::NORM_INF); }

TEST(StereoCalibration, FullFormRoundTrips) {
  const TempDir dir;
  const testing::KnownPair pair = testing::MakeKnownPair({320, 240}, 8.0);
  StereoCalibration written = pair.calibration;
  written.rms_px = 0.25;
  WriteStereoCalibration(written, dir.File("calib.yaml"));
  const StereoCalibration read = ReadStereoCalibration(dir.File("calib.yaml"));
  EXPECT_EQ(read.form, StereoCalibration::Form::kFull);
  EXPECT_EQ(read.image_size, cv::Size(320, 240));
  EXPECT_EQ(read.source, dir.File("calib.yaml"));
  EXPECT_DOUBLE_EQ(read.rms_px, 0.25);
  for (const auto& [a, b] : {std::pair{&read.K1, &written.K1}, {&read.D1, &written.D1},
                             {&read.K2, &written.K2}, {&read.D2, &written.D2},
                             {&read.R, &written.R}, {&read.T, &written.T}, {&read.R1, &written.R1},
                             {&read.R2, &written.R2}, {&read.P1, &written.P1},
                             {&read.P2, &written.P2}, {&read.Q, &written.Q}}) {
    EXPECT_LT(MaxDifference(*a, b->reshape(1, a->rows)), 1e-9);
  }
  EXPECT_NEAR(read.baseline_m(), cv::norm(written.T), 1e-6);
  EXPECT_TRUE(read.rectifies());
}

TEST(StereoCalibration, RectifiedFormHasIdentityRotationsAndItsQ) {
  const TempDir dir;
  const std::string path = dir.Write("calib.yaml",
                                     "%YAML:1.0\n---\nimage_width: 752\nimage_height: 480\n"
                                     "P1: !!opencv-matrix\n  rows: 3\n  cols: 4\n  dt: d\n"
                                     "  data: [436.2, 0, 364.4, 0, 0, 436.2, 257.0, 0, 0, 0, 1, 0]\n"
                                     "P2: !!opencv-matrix\n  rows: 3\n  cols: 4\n  dt: d\n"
                                     "  data: [436.2, 0, 364.4, -48.0, 0, 436.2, 257.0, 0, 0, 0, 1, 0]\n");
  const StereoCalibration c = ReadStereoCalibration(path);
  EXPECT_EQ(c.form, StereoCalibration::Form::kRectified);
  EXPECT_FALSE(c.rectifies());
  EXPECT_DOUBLE_EQ(c.focal_px(), 436.2);
  EXPECT_DOUBLE_EQ(c.cx(), 364.4);
  EXPECT_DOUBLE_EQ(c.cy(), 257.0);
  EXPECT_NEAR(c.baseline_m(), 48.0 / 436.2, 1e-12);
  EXPECT_EQ(MaxDifference(c.R1, cv::Mat::eye(3, 3, CV_64F)), 0.0);
  // Q takes (x, y, d) to (X, Y, Z) W: a point 2 m away at the principal point.
  const double d = 436.2 * c.baseline_m() / 2.0;
  cv::Mat point = c.Q * (cv::Mat_<double>(4, 1) << 364.4, 257.0, d, 1.0);
  EXPECT_NEAR(point.at<double>(2) / point.at<double>(3), 2.0, 1e-9);
  EXPECT_NEAR(point.at<double>(0) / point.at<double>(3), 0.0, 1e-9);
  // The rectified form writes and reads back as itself.
  WriteStereoCalibration(c, dir.File("again.yaml"));
  const StereoCalibration again = ReadStereoCalibration(dir.File("again.yaml"));
  EXPECT_EQ(again.form, StereoCalibration::Form::kRectified);
  EXPECT_LT(MaxDifference(again.P2, c.P2), 1e-12);
}

TEST(StereoCalibration, NominalFormPutsThePrincipalPointAtTheCentre) {
  const StereoCalibration c = NominalCalibration(300.0, 0.12, {320, 240}, "SEQ/sequence.yaml");
  EXPECT_EQ(c.form, StereoCalibration::Form::kNominal);
  EXPECT_DOUBLE_EQ(c.focal_px(), 300.0);
  EXPECT_DOUBLE_EQ(c.cx(), 159.5);
  EXPECT_DOUBLE_EQ(c.cy(), 119.5);
  EXPECT_DOUBLE_EQ(c.baseline_m(), 0.12);
  EXPECT_EQ(c.image_size, cv::Size(320, 240));
}

// OpenCV's stereo_calib sample names the intrinsics M1 and M2, and writes no image size.
TEST(StereoCalibration, ReadsM1AndM2AsK1AndK2) {
  const TempDir dir;
  const testing::KnownPair pair = testing::MakeKnownPair({320, 240}, 8.0);
  {
    cv::FileStorage out(dir.File("calib.yaml"), cv::FileStorage::WRITE);
    const StereoCalibration& c = pair.calibration;
    out << "image_width" << 320 << "image_height" << 240 << "M1" << c.K1 << "D1" << c.D1 << "M2"
        << c.K2 << "D2" << c.D2 << "R" << c.R << "T" << c.T;
  }
  const StereoCalibration c = ReadStereoCalibration(dir.File("calib.yaml"));
  EXPECT_EQ(c.form, StereoCalibration::Form::kFull);
  EXPECT_LT(MaxDifference(c.K2, pair.calibration.K2), 1e-12);
  // stereoRectify's own when the file has none.
  EXPECT_LT(MaxDifference(c.P2, pair.calibration.P2), 1e-6);
}

// The text of a full calibration with `key`'s line replaced by `line` ("" drops it).
std::string FullWith(const std::string& key, const std::string& line) {
  const std::string matrix = "!!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: ";
  std::vector<std::pair<std::string, std::string>> keys = {
      {"image_width", "image_width: 320"},
      {"image_height", "image_height: 240"},
      {"K1", "K1: " + matrix + "[300, 0, 160, 0, 300, 120, 0, 0, 1]"},
      {"D1", "D1: !!opencv-matrix\n  rows: 1\n  cols: 5\n  dt: d\n  data: [0, 0, 0, 0, 0]"},
      {"K2", "K2: " + matrix + "[300, 0, 160, 0, 300, 120, 0, 0, 1]"},
      {"D2", "D2: !!opencv-matrix\n  rows: 1\n  cols: 5\n  dt: d\n  data: [0, 0, 0, 0, 0]"},
      {"R", "R: " + matrix + "[1, 0, 0, 0, 1, 0, 0, 0, 1]"},
      {"T", "T: !!opencv-matrix\n  rows: 3\n  cols: 1\n  dt: d\n  data: [-0.1, 0, 0]"}};
  std::string text = "%YAML:1.0\n---\n";
  for (const auto& [name, value] : keys) {
    const std::string& chosen = name == key ? line : value;
    if (!chosen.empty()) text += chosen + "\n";
  }
  return text;
}

TEST(StereoCalibration, EachErrorNamesItsFileAndKey) {
  const TempDir dir;
  const std::string path = dir.File("calib.yaml");
  const auto error_of = [&](const std::string& text) {
    std::ofstream(path) << text;
    return InputErrorOf([&] { ReadStereoCalibration(path); });
  };
  EXPECT_EQ(error_of(FullWith("", "")), "");  // the base is valid
  EXPECT_NE(InputErrorOf([&] { ReadStereoCalibration(dir.File("none.yaml")); })
                .find("none.yaml: no such calibration file"),
            std::string::npos);
  EXPECT_NE(error_of("just: [text\n").find("not an OpenCV FileStorage"), std::string::npos);
  EXPECT_NE(error_of(FullWith("K2", "")).find("calib.yaml: K2 (or M2) is missing"),
            std::string::npos);
  EXPECT_NE(error_of(FullWith("T", "")).find(": T is missing"), std::string::npos);
  EXPECT_NE(error_of(FullWith("image_width", "")).find("image_width"), std::string::npos);
  EXPECT_NE(error_of(FullWith("R", "R: !!opencv-matrix\n  rows: 2\n  cols: 2\n  dt: d\n  data: "
                                   "[1, 0, 0, 1]"))
                .find("R must be 3x3, got 2x2"),
            std::string::npos);
  EXPECT_NE(error_of(FullWith("K1", "K1: !!opencv-matrix\n  rows: 3\n  cols: 3\n  dt: d\n  data: "
                                    "[-300, 0, 160, 0, 300, 120, 0, 0, 1]"))
                .find("K1 has a focal length that is not positive"),
            std::string::npos);
  EXPECT_NE(error_of(FullWith("T", "T: !!opencv-matrix\n  rows: 3\n  cols: 1\n  dt: d\n  data: "
                                   "[0, 0, 0]"))
                .find("T is zero"),
            std::string::npos);
  EXPECT_NE(error_of(FullWith("T", "T: !!opencv-matrix\n  rows: 3\n  cols: 1\n  dt: d\n  data: "
                                   "[.nan, 0, 0]"))
                .find("T has a value that is not finite"),
            std::string::npos);
  EXPECT_NE(error_of(FullWith("D1", "D1: !!opencv-matrix\n  rows: 1\n  cols: 3\n  dt: d\n  data: "
                                    "[0, 0, 0]"))
                .find("D1 must be a vector of 4, 5, 8, 12, 14 coefficients"),
            std::string::npos);
  const std::string p1 = "P1: !!opencv-matrix\n  rows: 3\n  cols: 4\n  dt: d\n  data: [300, 0, "
                         "160, 0, 0, 300, 120, 0, 0, 0, 1, 0]\n";
  const std::string size = "%YAML:1.0\n---\nimage_width: 320\nimage_height: 240\n";
  EXPECT_NE(error_of(size + p1).find("P2 is missing"), std::string::npos);
  EXPECT_NE(error_of(size + p1 + "P2: !!opencv-matrix\n  rows: 3\n  cols: 4\n  dt: d\n  data: "
                                 "[300, 0, 160, 0, 0, 300, 120, 0, 0, 0, 1, 0]\n")
                .find("P2 has a zero baseline"),
            std::string::npos);
  EXPECT_NE(error_of(size + "rms: 0.3\n").find("K1 (or M1) and P1 are both missing"),
            std::string::npos);
}

// A raw pair of a known calibration, rectified: each view is the rectified camera's.
TEST(Rectifier, RectifiesARawPairOfAKnownCalibration) {
  const testing::KnownPair pair = testing::MakeKnownPair({400, 300}, 10.0);
  // The raw views' rows differ by several pixels: there is something to rectify.
  cv::Mat left = pair.raw_left.clone(), right = pair.raw_right.clone();
  EXPECT_GT(MaxDifference(right, pair.rectified_right), 100.0);
  const Rectifier rectifier(pair.calibration);
  rectifier.Apply(&left, &right);
  // Away from the border (where the raw views saw nothing), the rectified views are the
  // rectified cameras' up to interpolation: the right is the left moved along its rows only.
  const cv::Rect inside(40, 40, 320, 220);
  for (const auto& [got, want] : {std::pair{&left, &pair.rectified_left},
                                  {&right, &pair.rectified_right}}) {
    cv::Mat difference;
    cv::absdiff((*got)(inside), (*want)(inside), difference);
    EXPECT_LT(cv::mean(difference)[0], 6.0);
    // A row off would differ as much as unrelated texture does (~40 grey levels).
    cv::Mat off;
    cv::absdiff((*got)(inside), testing::ShiftDown(*want, 1.0)(inside), off);
    EXPECT_GT(cv::mean(off)[0], 2.0 * cv::mean(difference)[0]);
  }
  cv::Mat small(100, 100, CV_8UC3);
  cv::Mat other = small.clone();
  EXPECT_NE(InputErrorOf([&] { rectifier.Apply(&small, &other); }).find("400x300"),
            std::string::npos);
}

// Where a folder sequence takes its calibration: --calib, SEQ/calib.yaml, sequence.yaml.
TEST(SequenceCalibration, ComesFromCalibThenCalibYamlThenSequenceYaml) {
  const TempDir dir;
  const std::string seq = testing::MakeFolderSequence(dir.File("seq"), 2, 64, 48);
  SequenceOptions options;
  options.source.folder = seq;
  options.resize = "native";
  EXPECT_EQ(OpenFrameSource(options)->info().calibration, nullptr);

  dir.Write("seq/sequence.yaml", "focal_px: 50\nbaseline_m: 0.1\n");
  auto info = OpenFrameSource(options)->info();
  ASSERT_NE(info.calibration, nullptr);
  EXPECT_EQ(info.calibration->form, StereoCalibration::Form::kNominal);
  EXPECT_DOUBLE_EQ(info.calibration->cx(), 31.5);

  WriteStereoCalibration(NominalCalibration(60, 0.2, {64, 48}, ""), dir.File("seq/calib.yaml"));
  info = OpenFrameSource(options)->info();
  EXPECT_EQ(info.calibration->form, StereoCalibration::Form::kRectified);
  EXPECT_DOUBLE_EQ(info.calibration->focal_px(), 60.0);

  WriteStereoCalibration(NominalCalibration(70, 0.2, {64, 48}, ""), dir.File("other.yaml"));
  options.source.calib = dir.File("other.yaml");
  info = OpenFrameSource(options)->info();
  EXPECT_DOUBLE_EQ(info.calibration->focal_px(), 70.0);
  EXPECT_EQ(info.calibration->source, dir.File("other.yaml"));

  // A calibration for other frames is refused, naming both sizes.
  WriteStereoCalibration(NominalCalibration(70, 0.2, {640, 480}, ""), dir.File("big.yaml"));
  options.source.calib = dir.File("big.yaml");
  const std::string error = InputErrorOf([&] { OpenFrameSource(options); });
  EXPECT_NE(error.find("640x480"), std::string::npos) << error;
  EXPECT_NE(error.find("64x48"), std::string::npos) << error;
}

TEST(SequenceCalibration, MonocularSourceRefusesACalibFile) {
  const TempDir dir;
  const std::string seq = testing::MakeFolderSequence(dir.File("seq"), 2, 64, 48, false);
  WriteStereoCalibration(NominalCalibration(70, 0.2, {64, 48}, ""), dir.File("calib.yaml"));
  SequenceOptions options;
  options.source.folder = seq;
  EXPECT_EQ(OpenFrameSource(options)->info().calibration, nullptr);
  options.source.calib = dir.File("calib.yaml");
  EXPECT_NE(ConfigErrorOf([&] { OpenFrameSource(options); }).find("monocular"),
            std::string::npos);
}

// A full calibration rectifies each raw pair before the working size.
TEST(SequenceCalibration, FullCalibrationRectifiesTheFrames) {
  const TempDir dir;
  const testing::KnownPair pair = testing::MakeKnownPair({400, 300}, 10.0);
  std::filesystem::create_directories(dir.path() / "seq" / "left");
  std::filesystem::create_directories(dir.path() / "seq" / "right");
  cv::imwrite(dir.File("seq/left/000000.png"), pair.raw_left);
  cv::imwrite(dir.File("seq/right/000000.png"), pair.raw_right);
  WriteStereoCalibration(pair.calibration, dir.File("seq/calib.yaml"));
  SequenceOptions options;
  options.source.folder = dir.File("seq");
  options.resize = "native";
  auto source = OpenFrameSource(options);
  ASSERT_NE(source->info().calibration, nullptr);
  EXPECT_TRUE(source->info().calibration->rectifies());
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  cv::Mat difference;
  const cv::Rect inside(40, 40, 320, 220);
  cv::absdiff(frame.right(inside), pair.rectified_right(inside), difference);
  EXPECT_LT(cv::mean(difference)[0], 6.0);
}

}  // namespace
}  // namespace attend
