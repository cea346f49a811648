#include "io/sequence.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

namespace fs = std::filesystem;

// Frame `index` of view `side` (0 left, 1 right) is uniform; its blue channel encodes the index
// and its green channel the side, so a test can tell exactly which image came out.
cv::Scalar Colour(int index, int side) { return cv::Scalar(10 * index, 60 + 100 * side, 200); }

cv::Mat Uniform(cv::Size size, const cv::Scalar& colour) { return cv::Mat(size, CV_8UC3, colour); }

void WriteImage(const std::string& path, const cv::Mat& image) {
  fs::create_directories(fs::path(path).parent_path());
  ASSERT_TRUE(cv::imwrite(path, image)) << path;
}

std::string FramePath(const testing::TempDir& dir, const std::string& view, int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.png", index);
  return (dir.path() / view / name).string();
}

// Writes frames 0..count-1 in the SPEC 3.1 folder layout; returns the folder.
std::string WriteFolder(const testing::TempDir& dir, int count, cv::Size size, bool stereo) {
  for (int i = 0; i < count; ++i) {
    WriteImage(FramePath(dir, "left", i), Uniform(size, Colour(i, 0)));
    if (stereo) WriteImage(FramePath(dir, "right", i), Uniform(size, Colour(i, 1)));
  }
  return dir.path().string();
}

void ExpectColour(const cv::Mat& image, const cv::Scalar& expected, double tolerance = 0.0) {
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.type(), CV_8UC3);
  double min_value = 0.0, max_value = 0.0;
  for (int c = 0; c < 3; ++c) {
    cv::Mat channel;
    cv::extractChannel(image, channel, c);
    cv::minMaxLoc(channel, &min_value, &max_value);
    EXPECT_LE(std::abs(min_value - expected[c]), tolerance) << "channel " << c;
    EXPECT_LE(std::abs(max_value - expected[c]), tolerance) << "channel " << c;
  }
}

SequenceOptions FolderOptions(const std::string& folder, const std::string& resize = "native") {
  SequenceOptions options;
  options.source.folder = folder;
  options.resize = resize;
  return options;
}

// ---------------------------------------------------------------------------------------------
// Options.

TEST(SequenceOptions, DefaultsAreValid) {
  // No source is valid for the options (`attend run` then takes the bundled sequence); Open()
  // is what needs one.
  SequenceOptions options;
  EXPECT_EQ(options.Check(), "");
  options.source.folder = "seq";
  EXPECT_EQ(options.Check(), "");
  EXPECT_EQ(options.width, 320);
  EXPECT_EQ(options.height, 240);
  EXPECT_EQ(options.resize, "pixels");
  EXPECT_EQ(options.stride, 1);
  EXPECT_EQ(options.first_frame, 0);
  EXPECT_EQ(options.last_frame, -1);
}

TEST(SequenceOptions, CheckNamesTheFieldAndConstraint) {
  const auto problem = [](auto change) {
    SequenceOptions options;
    options.source.folder = "seq";
    change(&options);
    return options.Check();
  };
  EXPECT_NE(problem([](SequenceOptions* o) { o->stride = 0; }).find("stride must be >= 1, got 0"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) { o->first_frame = -1; }).find("first_frame must be"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->first_frame = 5;
              o->last_frame = 4;
            }).find("last_frame must be -1 (to the end) or >= first_frame (5), got 4"),
            std::string::npos);
  EXPECT_EQ(problem([](SequenceOptions* o) {
              o->first_frame = 5;
              o->last_frame = 5;
            }),
            "");
  EXPECT_NE(problem([](SequenceOptions* o) { o->width = 0; }).find("width must be > 0"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) { o->height = -3; }).find("height must be > 0"),
            std::string::npos);
  EXPECT_EQ(problem([](SequenceOptions* o) {
              o->width = 0;
              o->height = 0;
              o->resize = "native";
            }),
            "");
  const std::string typo = problem([](SequenceOptions* o) { o->resize = "fitt"; });
  EXPECT_NE(
      typo.find("resize must be one of fit, pixels, stretch, native, got 'fitt' (did you mean "
                "'fit'?)"),
      std::string::npos)
      << typo;
  EXPECT_NE(
      problem([](SequenceOptions* o) { o->source.video = "v.avi"; }).find("at most one source"),
      std::string::npos);
  SequenceOptions half_pair;
  half_pair.source.left_video = "a.avi";
  EXPECT_NE(half_pair.Check().find("right_video must be set"), std::string::npos);
}

TEST(SequenceOptions, DescribeNamesTheSource) {
  SequenceOptions options;
  EXPECT_EQ(options.source.Describe(), "no source");
  options.source.folder = "data/seq";
  EXPECT_EQ(options.source.Describe(), "folder data/seq");
  options = {};
  options.source.left_video = "a.avi";
  options.source.right_video = "b.avi";
  EXPECT_EQ(options.source.Describe(), "videos a.avi + b.avi");
  options = {};
  options.source.side_by_side_video = "s.avi";
  EXPECT_EQ(options.source.Describe(), "side-by-side video s.avi");
  options = {};
  options.source.video = "m.avi";
  EXPECT_EQ(options.source.Describe(), "video m.avi");
  options = {};
  options.source.images = "otb/Dog1/img";
  EXPECT_EQ(options.source.Describe(), "images otb/Dog1/img");
}

TEST(SequenceOptions, ImagesIsOneSourceAmongOthers) {
  SequenceOptions options;
  options.source.images = "img";
  EXPECT_EQ(options.source.SourceCount(), 1);
  EXPECT_EQ(options.Check(), "");
  options.source.folder = "seq";
  EXPECT_EQ(options.source.SourceCount(), 2);
  EXPECT_NE(options.Check().find("at most one source may be set"), std::string::npos);
}

TEST(Sequence, InvalidOptionsOrNoSourceAreAConfigurationError) {
  SequenceOptions options;
  std::string message = ErrorOf<ConfigError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("no sequence source is set"), std::string::npos) << message;
  options.source.folder = "seq";
  options.stride = 0;
  message = ErrorOf<ConfigError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("stride must be >= 1"), std::string::npos) << message;
}

// ---------------------------------------------------------------------------------------------
// Folders.

TEST(Sequence, StereoFolderDeliversEveryFrameInOrder) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 4, {40, 30}, /*stereo=*/true);
  auto source = OpenFrameSource(FolderOptions(folder));
  const SequenceInfo& info = source->info();
  EXPECT_TRUE(info.stereo);
  EXPECT_EQ(info.frame_count, 4);
  EXPECT_EQ(info.native_size, cv::Size(40, 30));
  EXPECT_EQ(info.size, cv::Size(40, 30));
  EXPECT_DOUBLE_EQ(info.scale_x, 1.0);
  EXPECT_DOUBLE_EQ(info.scale_y, 1.0);
  EXPECT_EQ(info.name, dir.path().filename().string());
  EXPECT_DOUBLE_EQ(info.fps, 25.0);
  EXPECT_DOUBLE_EQ(info.focal_px, 0.0);
  EXPECT_DOUBLE_EQ(info.baseline_m, 0.0);
  EXPECT_EQ(info.folder, folder);

  StereoFrame frame;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(source->Next(&frame)) << i;
    EXPECT_EQ(frame.index, i);
    ExpectColour(frame.left, Colour(i, 0));
    ExpectColour(frame.right, Colour(i, 1));
    EXPECT_EQ(frame.left_path, FramePath(dir, "left", i));
    EXPECT_EQ(frame.right_path, FramePath(dir, "right", i));
  }
  EXPECT_FALSE(source->Next(&frame));
  EXPECT_FALSE(source->Next(&frame));
}

TEST(Sequence, MonocularFolderHasNoRightView) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 3, {20, 10}, /*stereo=*/false);
  auto source = OpenFrameSource(FolderOptions(folder));
  EXPECT_FALSE(source->info().stereo);
  EXPECT_EQ(source->info().frame_count, 3);
  StereoFrame frame;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(source->Next(&frame));
    EXPECT_EQ(frame.index, i);
    ExpectColour(frame.left, Colour(i, 0));
    EXPECT_TRUE(frame.right.empty());
    EXPECT_EQ(frame.right_path, "");
  }
  EXPECT_FALSE(source->Next(&frame));
}

TEST(Sequence, FramesAreMatchedBySortedNameAndOnlyImageExtensionsCount) {
  testing::TempDir dir;
  const cv::Size size(8, 6);
  // Written out of order; the index is the position in the sorted list, not the number in the
  // name. Upper-case extensions count; other files are ignored.
  const std::vector<std::string> names = {"f30.PNG", "f10.png", "f20.ppm", "f40.Jpeg", "f50.jpg"};
  const std::vector<int> sorted_position = {2, 0, 1, 3, 4};
  for (size_t i = 0; i < names.size(); ++i) {
    const cv::Scalar colour = Colour(sorted_position[i], 0);
    WriteImage((dir.path() / "left" / names[i]).string(), Uniform(size, colour));
  }
  dir.Write("left/notes.txt", "not a frame");
  dir.Write("left/f00.bmp", "not matched either");
  fs::create_directories(dir.path() / "left" / "sub.png");  // a folder, not a frame
  auto source = OpenFrameSource(FolderOptions(dir.path().string()));
  EXPECT_FALSE(source->info().stereo);
  EXPECT_EQ(source->info().frame_count, 5);
  const std::vector<std::string> expected_files = {"f10.png", "f20.ppm", "f30.PNG", "f40.Jpeg",
                                                   "f50.jpg"};
  StereoFrame frame;
  for (int i = 0; i < 5; ++i) {
    ASSERT_TRUE(source->Next(&frame));
    EXPECT_EQ(frame.index, i);
    EXPECT_EQ(fs::path(frame.left_path).filename(), expected_files[i]);
    // JPEG is lossy, but a uniform block survives within a few levels.
    ExpectColour(frame.left, Colour(i, 0), i >= 3 ? 4.0 : 0.0);
  }
  EXPECT_FALSE(source->Next(&frame));
}

// ---------------------------------------------------------------------------------------------
// Plain folders of frames (--images).

SequenceOptions ImagesOptions(const std::string& folder) {
  SequenceOptions options;
  options.source.images = folder;
  options.resize = "native";
  return options;
}

TEST(Sequence, ImageFolderIsMonocularWithFramesInSortedNameOrder) {
  testing::TempDir dir;
  const cv::Size size(8, 6);
  // The folder itself holds the frames, as an OTB img/ does; same rules as left/.
  const std::vector<std::string> names = {"0003.JPG", "0001.png", "0002.pgm", "0004.jpeg",
                                          "0010.Ppm"};
  const std::vector<int> sorted_position = {2, 0, 1, 3, 4};
  for (size_t i = 0; i < names.size(); ++i) {
    // Grey values so that the .pgm frame can hold its colour exactly.
    const int v = 10 * sorted_position[i] + 20;
    const bool pgm = names[i].size() > 4 && names[i].substr(names[i].size() - 4) == ".pgm";
    WriteImage((dir.path() / "img" / names[i]).string(),
               pgm ? cv::Mat(size, CV_8UC1, cv::Scalar(v)) : Uniform(size, cv::Scalar(v, v, v)));
  }
  dir.Write("img/groundtruth_rect.txt", "1,2,3,4");
  dir.Write("img/0000.bmp", "not a frame");
  fs::create_directories(dir.path() / "img" / "0000.png");  // a folder, not a frame
  const std::string folder = (dir.path() / "img").string();
  SequenceOptions options = ImagesOptions(folder);
  options.first_frame = 1;
  auto source = OpenFrameSource(options);
  const SequenceInfo& info = source->info();
  EXPECT_FALSE(info.stereo);
  EXPECT_EQ(info.frame_count, 4);
  EXPECT_EQ(info.name, "img");
  EXPECT_EQ(info.folder, "");  // no gt/ below a plain folder
  EXPECT_EQ(info.native_size, size);
  const std::vector<std::string> expected_files = {"0002.pgm", "0003.JPG", "0004.jpeg",
                                                   "0010.Ppm"};
  StereoFrame frame;
  for (int i = 1; i < 5; ++i) {
    ASSERT_TRUE(source->Next(&frame));
    EXPECT_EQ(frame.index, i);
    EXPECT_EQ(fs::path(frame.left_path).filename(), expected_files[i - 1]);
    EXPECT_TRUE(frame.right.empty());
    EXPECT_EQ(frame.right_path, "");
    const int v = 10 * i + 20;
    ExpectColour(frame.left, cv::Scalar(v, v, v), 4.0);  // JPEG within a few levels
  }
  EXPECT_FALSE(source->Next(&frame));

  // The listing is public, for `attend track` and others.
  const std::vector<std::string> files = ListFrameFiles(folder, "test");
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(fs::path(files[0]).filename(), "0001.png");
  EXPECT_EQ(fs::path(files[4]).filename(), "0010.Ppm");
}

TEST(Sequence, ImageFolderIsScaledToTheWorkingSize) {
  testing::TempDir dir;
  WriteImage((dir.path() / "a.png").string(), Uniform({640, 480}, Colour(1, 0)));
  SequenceOptions options = ImagesOptions(dir.path().string());
  options.resize = "fit";
  auto source = OpenFrameSource(options);
  EXPECT_EQ(source->info().native_size, cv::Size(640, 480));
  EXPECT_EQ(source->info().size, cv::Size(320, 240));
  EXPECT_DOUBLE_EQ(source->info().scale_x, 0.5);
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.left.size(), cv::Size(320, 240));
  ExpectColour(frame.left, Colour(1, 0));
}

TEST(Sequence, BadImageFoldersAndFramesAreBadInput) {
  testing::TempDir dir;
  const std::string missing = (dir.path() / "nope").string();
  std::string message = ErrorOf<InputError>([&] { OpenFrameSource(ImagesOptions(missing)); });
  EXPECT_NE(message.find("images " + missing + ": no such folder"), std::string::npos) << message;

  const std::string file = dir.Write("plain.txt", "x");
  message = ErrorOf<InputError>([&] { OpenFrameSource(ImagesOptions(file)); });
  EXPECT_NE(message.find("not a folder"), std::string::npos) << message;

  fs::create_directories(dir.path() / "empty");
  dir.Write("empty/readme.txt", "no frames here");
  const std::string empty = (dir.path() / "empty").string();
  message = ErrorOf<InputError>([&] { OpenFrameSource(ImagesOptions(empty)); });
  EXPECT_NE(message.find("images " + empty + ": no frames (expected files ending in .png"),
            std::string::npos)
      << message;

  // A frame that is not an image is reported with its index and path when reached.
  const std::string bad = (dir.path() / "bad").string();
  WriteImage(bad + "/1.png", Uniform({8, 6}, Colour(0, 0)));
  dir.Write("bad/2.png", "not a png");
  WriteImage(bad + "/3.png", Uniform({8, 6}, Colour(2, 0)));
  WriteImage(bad + "/4.png", Uniform({9, 6}, Colour(3, 0)));
  auto source = OpenFrameSource(ImagesOptions(bad));
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  message = ErrorOf<InputError>([&] { source->Next(&frame); });
  EXPECT_NE(message.find("frame 1 (" + bad + "/2.png): cannot be read or decoded"),
            std::string::npos)
      << message;
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.index, 2);
  message = ErrorOf<InputError>([&] { source->Next(&frame); });
  EXPECT_NE(message.find("frame 3 (" + bad + "/4.png): size 9x6 differs from the first frame's 8x6"),
            std::string::npos)
      << message;
}

TEST(Sequence, GreyAndSixteenBitImagesBecomeEightBitBgr) {
  testing::TempDir dir;
  const cv::Size size(6, 4);
  WriteImage((dir.path() / "left" / "000000.pgm").string(), cv::Mat(size, CV_8UC1, 77));
  // 16-bit samples keep their high byte: 0x4D7F -> 0x4D = 77.
  WriteImage((dir.path() / "left" / "000001.png").string(), cv::Mat(size, CV_16UC1, 0x4D7F));
  WriteImage((dir.path() / "left" / "000002.png").string(),
             cv::Mat(size, CV_16UC3, cv::Scalar(0x0A00, 0x1400, 0xFFFF)));
  auto source = OpenFrameSource(FolderOptions(dir.path().string()));
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  ExpectColour(frame.left, cv::Scalar(77, 77, 77));
  ASSERT_TRUE(source->Next(&frame));
  ExpectColour(frame.left, cv::Scalar(77, 77, 77));
  ASSERT_TRUE(source->Next(&frame));
  ExpectColour(frame.left, cv::Scalar(10, 20, 255));
}

TEST(Sequence, RangeAndStrideSelectSourceIndices) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 10, {8, 6}, /*stereo=*/true);
  struct Case {
    int first, last, stride;
    std::vector<int> expected;
  };
  const std::vector<Case> cases = {
      {2, 8, 3, {2, 5, 8}},  // last included
      {2, 7, 3, {2, 5}},     // stride stops before last
      {3, -1, 4, {3, 7}},    // to the end
      {8, 20, 1, {8, 9}},    // a last frame beyond the end stops at the end
      {9, -1, 5, {9}},       // only the last frame
      {0, 0, 1, {0}},
  };
  for (const Case& c : cases) {
    SequenceOptions options = FolderOptions(folder);
    options.first_frame = c.first;
    options.last_frame = c.last;
    options.stride = c.stride;
    auto source = OpenFrameSource(options);
    EXPECT_EQ(source->info().frame_count, static_cast<int>(c.expected.size()))
        << c.first << ":" << c.last << "/" << c.stride;
    StereoFrame frame;
    for (int expected : c.expected) {
      ASSERT_TRUE(source->Next(&frame));
      EXPECT_EQ(frame.index, expected);
      ExpectColour(frame.left, Colour(expected, 0));
      ExpectColour(frame.right, Colour(expected, 1));
      EXPECT_EQ(frame.left_path, FramePath(dir, "left", expected));
    }
    EXPECT_FALSE(source->Next(&frame)) << c.first << ":" << c.last << "/" << c.stride;
  }
}

TEST(Sequence, RangeStartingBeyondTheLastFrameIsBadInput) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 3, {8, 6}, /*stereo=*/true);
  SequenceOptions options = FolderOptions(folder);
  options.first_frame = 3;
  const std::string message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("starts at frame 3 but the source has 3 frames (0..2)"), std::string::npos)
      << message;
  EXPECT_NE(message.find(folder), std::string::npos) << message;
}

TEST(Sequence, ResizeModesGiveTheWorkingSizeAndScale) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 2, {64, 48}, /*stereo=*/true);
  struct Case {
    std::string resize;
    int width, height;
    cv::Size size;
    double scale_x, scale_y;
  };
  const std::vector<Case> cases = {
      {"native", 0, 0, {64, 48}, 1.0, 1.0},
      {"fit", 32, 32, {32, 24}, 0.5, 0.5},     // width limits
      {"fit", 100, 12, {16, 12}, 0.25, 0.25},  // height limits
      {"fit", 128, 128, {128, 96}, 2.0, 2.0},  // small frames are enlarged
      {"fit", 32, 24, {32, 24}, 0.5, 0.5},     // same aspect ratio
      // pixels: width x height pixels with the frames' aspect ratio, whatever the box's shape
      {"pixels", 32, 24, {32, 24}, 0.5, 0.5},
      {"pixels", 16, 48, {32, 24}, 0.5, 0.5},
      {"pixels", 128, 96, {128, 96}, 2.0, 2.0},
      {"stretch", 32, 32, {32, 32}, 0.5, 32.0 / 48.0},
      {"stretch", 80, 24, {80, 24}, 1.25, 0.5},
  };
  for (const Case& c : cases) {
    SequenceOptions options = FolderOptions(folder, c.resize);
    options.width = c.width;
    options.height = c.height;
    auto source = OpenFrameSource(options);
    const SequenceInfo& info = source->info();
    SCOPED_TRACE(c.resize + " " + std::to_string(c.width) + "x" + std::to_string(c.height));
    EXPECT_EQ(info.native_size, cv::Size(64, 48));
    EXPECT_EQ(info.size, c.size);
    EXPECT_DOUBLE_EQ(info.scale_x, c.scale_x);
    EXPECT_DOUBLE_EQ(info.scale_y, c.scale_y);
    StereoFrame frame;
    for (int i = 0; i < 2; ++i) {
      ASSERT_TRUE(source->Next(&frame));
      EXPECT_EQ(frame.left.size(), c.size);
      EXPECT_EQ(frame.right.size(), c.size);
      EXPECT_TRUE(frame.left.isContinuous());
      ExpectColour(frame.left, Colour(i, 0));  // uniform images stay uniform
      ExpectColour(frame.right, Colour(i, 1));
    }
  }
}

TEST(Sequence, FitKeepsTheAspectRatioOfWideFrames) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 1, {128, 72}, /*stereo=*/false);  // 16:9
  auto source = OpenFrameSource(FolderOptions(folder, "fit"));  // default box 320x240
  EXPECT_EQ(source->info().size, cv::Size(320, 180));
  EXPECT_DOUBLE_EQ(source->info().scale_x, 2.5);
  EXPECT_DOUBLE_EQ(source->info().scale_y, 2.5);
}

TEST(Sequence, ShrinkingAveragesAndEnlargingInterpolates) {
  testing::TempDir dir;
  // Columns repeat 0, 0, 0, 240. Shrinking by 4 with area averaging gives 60 everywhere; a
  // point-sampling filter would give 0 or 120.
  cv::Mat stripes(8, 16, CV_8UC3, cv::Scalar::all(0));
  for (int x = 3; x < 16; x += 4) stripes.col(x).setTo(cv::Scalar::all(240));
  WriteImage((dir.path() / "left" / "000000.png").string(), stripes);
  SequenceOptions options = FolderOptions(dir.path().string(), "stretch");
  options.width = 4;
  options.height = 2;
  StereoFrame frame;
  auto shrink = OpenFrameSource(options);
  ASSERT_TRUE(shrink->Next(&frame));
  ExpectColour(frame.left, cv::Scalar::all(60));

  // Two columns, 0 and 200, enlarged to eight: bilinear produces values in between.
  testing::TempDir dir2;
  cv::Mat edge(2, 2, CV_8UC3, cv::Scalar::all(0));
  edge.col(1).setTo(cv::Scalar::all(200));
  WriteImage((dir2.path() / "left" / "000000.png").string(), edge);
  options = FolderOptions(dir2.path().string(), "stretch");
  options.width = 8;
  options.height = 2;
  auto enlarge = OpenFrameSource(options);
  ASSERT_TRUE(enlarge->Next(&frame));
  ASSERT_EQ(frame.left.size(), cv::Size(8, 2));
  EXPECT_EQ(frame.left.at<cv::Vec3b>(0, 0)[0], 0);
  EXPECT_EQ(frame.left.at<cv::Vec3b>(0, 7)[0], 200);
  int in_between = 0;
  for (int x = 0; x < 8; ++x) {
    const int value = frame.left.at<cv::Vec3b>(0, x)[0];
    if (value > 0 && value < 200) ++in_between;
  }
  EXPECT_GE(in_between, 2);
}

// ---------------------------------------------------------------------------------------------
// sequence.yaml.

TEST(Sequence, SequenceYamlSetsNameFpsAndCalibration) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 2, {8, 6}, /*stereo=*/true);
  dir.Write("sequence.yaml",
            "name: corridor\nfps: 12.5\nfocal_px: 410.25\nbaseline_m: 0.12\n"
            "generator: {tool: attend synth, seed: 7}\nframes: 2\n");
  auto source = OpenFrameSource(FolderOptions(folder));
  const SequenceInfo& info = source->info();
  EXPECT_EQ(info.name, "corridor");
  EXPECT_DOUBLE_EQ(info.fps, 12.5);
  EXPECT_DOUBLE_EQ(info.focal_px, 410.25);
  EXPECT_DOUBLE_EQ(info.baseline_m, 0.12);
  EXPECT_EQ(info.frame_count, 2);
}

TEST(Sequence, BadSequenceYamlIsBadInputWithItsLine) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 1, {8, 6}, /*stereo=*/false);
  const std::string yaml = (dir.path() / "sequence.yaml").string();
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"name: a\nfsp: 30\n", yaml + ":2: unknown key 'fsp' (did you mean 'fps'?)"},
      {"name: a\nfocal_px: 400\nfps: fast\n", yaml + ":3: fps: expected a number, got 'fast'"},
      {"baseline_m: -0.1\n", yaml + ":1: baseline_m: value -0.1 out of range: must be >= 0"},
      {"name: [a, b\n", yaml + ":"},
  };
  for (const Case& c : cases) {
    dir.Write("sequence.yaml", c.text);
    try {
      OpenFrameSource(FolderOptions(folder));
      ADD_FAILURE() << "no error for " << c.text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.status(), ExitStatus::kBadInput);
      EXPECT_NE(std::string(e.what()).find(c.expected), std::string::npos) << e.what();
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Bad folders and frames.

TEST(Sequence, MissingOrEmptyFoldersAreBadInput) {
  testing::TempDir dir;
  const std::string missing = (dir.path() / "nope").string();
  std::string message = ErrorOf<InputError>([&] { OpenFrameSource(FolderOptions(missing)); });
  EXPECT_NE(message.find("folder " + missing + ": no such folder"), std::string::npos) << message;

  fs::create_directories(dir.path() / "noleft" / "right");
  message = ErrorOf<InputError>(
      [&] { OpenFrameSource(FolderOptions((dir.path() / "noleft").string())); });
  EXPECT_NE(message.find("no left/ folder"), std::string::npos) << message;

  fs::create_directories(dir.path() / "empty" / "left");
  dir.Write("empty/left/readme.txt", "no frames here");
  message = ErrorOf<InputError>(
      [&] { OpenFrameSource(FolderOptions((dir.path() / "empty").string())); });
  EXPECT_NE(message.find("no frames in " + (dir.path() / "empty" / "left").string()),
            std::string::npos)
      << message;

  const std::string file = dir.Write("plain.txt", "x");
  message = ErrorOf<InputError>([&] { OpenFrameSource(FolderOptions(file)); });
  EXPECT_NE(message.find("not a folder"), std::string::npos) << message;
}

TEST(Sequence, LeftAndRightCountsThatDifferAreBadInput) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 5, {8, 6}, /*stereo=*/true);
  fs::remove(FramePath(dir, "right", 4));
  const std::string message =
      ErrorOf<InputError>([&] { OpenFrameSource(FolderOptions(folder)); });
  EXPECT_NE(message.find("folder " + folder + ": left/ has 5 frames but right/ has 4"),
            std::string::npos)
      << message;
}

TEST(Sequence, LeftAndRightSizesThatDifferAreBadInput) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 4, {8, 6}, /*stereo=*/true);
  // Frame 0: found when opening.
  WriteImage(FramePath(dir, "right", 0), Uniform({9, 6}, Colour(0, 1)));
  std::string message = ErrorOf<InputError>([&] { OpenFrameSource(FolderOptions(folder)); });
  EXPECT_NE(message.find("frame 0 (" + FramePath(dir, "right", 0) +
                         "): size 9x6 differs from the left image's 8x6"),
            std::string::npos)
      << message;

  // Frame 2: found when it is reached.
  WriteImage(FramePath(dir, "right", 0), Uniform({8, 6}, Colour(0, 1)));
  WriteImage(FramePath(dir, "right", 2), Uniform({8, 7}, Colour(2, 1)));
  auto source = OpenFrameSource(FolderOptions(folder));
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  ASSERT_TRUE(source->Next(&frame));
  message = ErrorOf<InputError>([&] { source->Next(&frame); });
  EXPECT_NE(message.find("frame 2 (" + FramePath(dir, "right", 2) + "): size 8x7"),
            std::string::npos)
      << message;
}

TEST(Sequence, FrameWhoseSizeDiffersFromTheFirstIsBadInputWhenReached) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 4, {8, 6}, /*stereo=*/false);
  WriteImage(FramePath(dir, "left", 2), Uniform({6, 8}, Colour(2, 0)));
  SequenceOptions options = FolderOptions(folder, "fit");
  options.width = 4;
  options.height = 3;
  auto source = OpenFrameSource(options);
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.index, 1);
  const std::string message = ErrorOf<InputError>([&] { source->Next(&frame); });
  EXPECT_NE(message.find("frame 2 (" + FramePath(dir, "left", 2) +
                         "): size 6x8 differs from the first frame's 8x6"),
            std::string::npos)
      << message;
}

TEST(Sequence, CorruptFrameInTheMiddleComesAfterTheGoodOnes) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 5, {8, 6}, /*stereo=*/true);
  const std::string bad = FramePath(dir, "right", 2);
  { std::ofstream(bad, std::ios::trunc) << "this is not a PNG file"; }
  auto source = OpenFrameSource(FolderOptions(folder));
  std::vector<StereoFrame> delivered(2);
  ASSERT_TRUE(source->Next(&delivered[0]));
  ASSERT_TRUE(source->Next(&delivered[1]));
  StereoFrame frame;
  try {
    source->Next(&frame);
    ADD_FAILURE() << "the corrupt frame was not reported";
  } catch (const InputError& e) {
    EXPECT_EQ(e.status(), ExitStatus::kBadInput);
    EXPECT_NE(std::string(e.what()).find("frame 2 (" + bad + "): cannot be read or decoded"),
              std::string::npos)
        << e.what();
  }
  // Frames handed out before the error are intact.
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(delivered[i].index, i);
    ExpectColour(delivered[i].left, Colour(i, 0));
    ExpectColour(delivered[i].right, Colour(i, 1));
  }
  // A caller that chooses to go on gets the frame after the bad one.
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.index, 3);
  ExpectColour(frame.left, Colour(3, 0));
}

TEST(Sequence, ReadAheadGivesTheSameFramesAndErrorsInOrder) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 5, {8, 6}, /*stereo=*/true);
  const std::string bad = FramePath(dir, "left", 2);
  { std::ofstream(bad, std::ios::trunc) << "this is not a PNG file"; }
  auto source = ReadAhead(OpenFrameSource(FolderOptions(folder)));
  EXPECT_EQ(source->info().frame_count, 5);
  EXPECT_TRUE(source->info().stereo);
  StereoFrame frame;
  for (int i = 0; i < 5; ++i) {
    if (i == 2) {
      try {
        source->Next(&frame);
        ADD_FAILURE() << "the corrupt frame was not reported";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("frame 2 (" + bad + "): cannot be read or decoded"),
                  std::string::npos)
            << e.what();
      }
      continue;
    }
    ASSERT_TRUE(source->Next(&frame)) << i;
    EXPECT_EQ(frame.index, i);
    ExpectColour(frame.left, Colour(i, 0));
    ExpectColour(frame.right, Colour(i, 1));
  }
  EXPECT_FALSE(source->Next(&frame));
  EXPECT_FALSE(source->Next(&frame));
}

// Counts the frames asked of it; frame i is a 4x4 image of value i.
class CountingSource final : public FrameSource {
 public:
  const SequenceInfo& info() const override { return info_; }
  bool Next(StereoFrame* frame) override {
    const int index = calls_.fetch_add(1);
    if (index >= 3) return false;
    frame->index = index;
    frame->left = cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(index));
    return true;
  }
  std::atomic<int>* calls() { return &calls_; }

 private:
  SequenceInfo info_;
  std::atomic<int> calls_{0};
};

TEST(Sequence, ReadAheadReadsTheNextFrameWhileTheCallerWorks) {
  auto counting = std::make_unique<CountingSource>();
  std::atomic<int>* calls = counting->calls();
  auto source = ReadAhead(std::move(counting));
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.index, 0);
  // Frame 1 is read without a further Next(): within seconds, however loaded the machine.
  for (int waited = 0; calls->load() < 2 && waited < 10000; ++waited) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(calls->load(), 2);
  // One frame ahead, no more.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_EQ(calls->load(), 2);
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.index, 1);
  EXPECT_EQ(frame.left.at<cv::Vec3b>(0, 0), cv::Vec3b(1, 1, 1));
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.index, 2);
  EXPECT_FALSE(source->Next(&frame));
}

TEST(Sequence, CorruptFirstFrameIsReportedByOpen) {
  testing::TempDir dir;
  const std::string folder = WriteFolder(dir, 3, {8, 6}, /*stereo=*/false);
  SequenceOptions options = FolderOptions(folder);
  options.first_frame = 1;
  { std::ofstream(FramePath(dir, "left", 1), std::ios::trunc) << "garbage"; }
  const std::string message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("frame 1 (" + FramePath(dir, "left", 1) + ")"), std::string::npos)
      << message;
}

// ---------------------------------------------------------------------------------------------
// Videos. MJPG is lossy, so uniform frames come back within a few levels; the levels used are
// grey (no chroma loss) and 40 apart.

constexpr double kVideoTolerance = 8.0;
constexpr double kVideoFps = 10.0;

cv::Scalar VideoGrey(int index, int side) {
  return cv::Scalar::all(side == 0 ? 20 + 40 * index : 230 - 40 * index);
}

// Writes an MJPG AVI; false when this OpenCV build cannot write one.
bool WriteVideo(const std::string& path, const std::vector<cv::Mat>& frames) {
  cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), kVideoFps,
                         frames.front().size());
  if (!writer.isOpened()) return false;
  for (const cv::Mat& frame : frames) writer.write(frame);
  writer.release();
  return fs::exists(path) && fs::file_size(path) > 0;
}

std::vector<cv::Mat> VideoFrames(int count, cv::Size size, int side) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) frames.push_back(Uniform(size, VideoGrey(i, side)));
  return frames;
}

#define ATTEND_WRITE_VIDEO_OR_SKIP(path, frames)                                             \
  if (!WriteVideo(path, frames)) {                                                           \
    GTEST_SKIP() << "this OpenCV build cannot write MJPG .avi video, so video input is not " \
                    "tested";                                                                \
  }

TEST(Sequence, PairOfVideosWithStride) {
  testing::TempDir dir;
  const std::string left = dir.File("cam_left.avi");
  const std::string right = dir.File("cam_right.avi");
  ATTEND_WRITE_VIDEO_OR_SKIP(left, VideoFrames(5, {32, 24}, 0));
  ATTEND_WRITE_VIDEO_OR_SKIP(right, VideoFrames(5, {32, 24}, 1));
  SequenceOptions options;
  options.source.left_video = left;
  options.source.right_video = right;
  options.resize = "native";
  options.stride = 2;
  auto source = OpenFrameSource(options);
  const SequenceInfo& info = source->info();
  EXPECT_TRUE(info.stereo);
  EXPECT_EQ(info.name, "cam_left");
  EXPECT_DOUBLE_EQ(info.fps, kVideoFps);
  EXPECT_EQ(info.frame_count, 3);
  EXPECT_EQ(info.native_size, cv::Size(32, 24));
  EXPECT_EQ(info.folder, "");
  std::vector<StereoFrame> frames;
  StereoFrame frame;
  while (source->Next(&frame)) frames.push_back(frame);
  ASSERT_EQ(frames.size(), 3u);
  // Checked after reading everything: earlier frames must not share buffers with later ones.
  for (int k = 0; k < 3; ++k) {
    const int index = 2 * k;
    EXPECT_EQ(frames[k].index, index);
    ExpectColour(frames[k].left, VideoGrey(index, 0), kVideoTolerance);
    ExpectColour(frames[k].right, VideoGrey(index, 1), kVideoTolerance);
    EXPECT_EQ(frames[k].left_path, left + "#" + std::to_string(index));
    EXPECT_EQ(frames[k].right_path, right + "#" + std::to_string(index));
  }
}

TEST(Sequence, PairOfVideosWithDifferentLengthsIsBadInput) {
  testing::TempDir dir;
  const std::string left = dir.File("l.avi");
  const std::string right = dir.File("r.avi");
  ATTEND_WRITE_VIDEO_OR_SKIP(left, VideoFrames(4, {32, 24}, 0));
  ATTEND_WRITE_VIDEO_OR_SKIP(right, VideoFrames(3, {32, 24}, 1));
  SequenceOptions options;
  options.source.left_video = left;
  options.source.right_video = right;
  const std::string message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("the left video has 4 frames but the right video has 3"),
            std::string::npos)
      << message;
}

TEST(Sequence, SideBySideVideoIsSplitIntoHalves) {
  testing::TempDir dir;
  const std::string path = dir.File("sbs.avi");
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 4; ++i) {
    cv::Mat both(24, 64, CV_8UC3);
    both(cv::Rect(0, 0, 32, 24)).setTo(VideoGrey(i, 0));
    both(cv::Rect(32, 0, 32, 24)).setTo(VideoGrey(i, 1));
    frames.push_back(both);
  }
  ATTEND_WRITE_VIDEO_OR_SKIP(path, frames);
  SequenceOptions options;
  options.source.side_by_side_video = path;
  options.width = 16;
  options.height = 16;
  options.resize = "fit";
  auto source = OpenFrameSource(options);
  const SequenceInfo& info = source->info();
  EXPECT_TRUE(info.stereo);
  EXPECT_EQ(info.name, "sbs");
  EXPECT_EQ(info.native_size, cv::Size(32, 24));
  EXPECT_EQ(info.size, cv::Size(16, 12));
  EXPECT_DOUBLE_EQ(info.scale_x, 0.5);
  EXPECT_EQ(info.frame_count, 4);
  StereoFrame frame;
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(source->Next(&frame));
    EXPECT_EQ(frame.index, i);
    EXPECT_EQ(frame.left.size(), cv::Size(16, 12));
    // Away from the seam, where the codec blurs the two halves together.
    ExpectColour(frame.left(cv::Rect(0, 0, 12, 12)), VideoGrey(i, 0), kVideoTolerance);
    ExpectColour(frame.right(cv::Rect(4, 0, 12, 12)), VideoGrey(i, 1), kVideoTolerance);
    EXPECT_EQ(frame.left_path, path + "#" + std::to_string(i));
  }
  EXPECT_FALSE(source->Next(&frame));
}

TEST(Sequence, SideBySideVideoOfOddWidthIsBadInput) {
  // OpenCV's video writer rounds widths down to even, so the odd-width "video" is an image
  // sequence pattern, which OpenCV's FFmpeg backend reads like a video.
  testing::TempDir dir;
  for (int i = 0; i < 2; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "sbs_%03d.png", i);
    WriteImage(dir.File(name), Uniform({63, 20}, Colour(i, 0)));
  }
  SequenceOptions options;
  options.source.side_by_side_video = dir.File("sbs_%03d.png");
  cv::VideoCapture probe(options.source.side_by_side_video);
  if (!probe.isOpened()) GTEST_SKIP() << "this OpenCV build cannot read image-sequence patterns";
  probe.release();
  const std::string message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("frame 0 (" + options.source.side_by_side_video +
                         "#0): width 63 is odd, so it cannot be split"),
            std::string::npos)
      << message;
}

TEST(Sequence, MonocularVideoWithRange) {
  testing::TempDir dir;
  const std::string path = dir.File("walk.avi");
  ATTEND_WRITE_VIDEO_OR_SKIP(path, VideoFrames(6, {32, 24}, 0));
  SequenceOptions options;
  options.source.video = path;
  options.resize = "native";
  options.first_frame = 1;
  options.last_frame = 3;
  auto source = OpenFrameSource(options);
  EXPECT_FALSE(source->info().stereo);
  EXPECT_EQ(source->info().name, "walk");
  EXPECT_EQ(source->info().frame_count, 3);
  StereoFrame frame;
  for (int index = 1; index <= 3; ++index) {
    ASSERT_TRUE(source->Next(&frame));
    EXPECT_EQ(frame.index, index);
    ExpectColour(frame.left, VideoGrey(index, 0), kVideoTolerance);
    EXPECT_TRUE(frame.right.empty());
    EXPECT_EQ(frame.right_path, "");
  }
  EXPECT_FALSE(source->Next(&frame));

  options.first_frame = 6;
  options.last_frame = -1;
  const std::string message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("starts at frame 6 but the source has 6 frames"), std::string::npos)
      << message;
}

// A video cut short keeps the header that announces all its frames: the frames that are there
// are delivered, then the end is an error naming how many were announced (issue 30: it used to
// end quietly, the run saying frames_in_range 20 over 10 frames).
TEST(Sequence, AVideoCutShortIsBadInputAtTheFrameWhereItEnds) {
  testing::TempDir dir;
  const std::string path = dir.File("cut.avi");
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 20; ++i) {
    cv::Mat frame(48, 64, CV_8UC3);
    cv::randu(frame, cv::Scalar::all(0), cv::Scalar::all(255));
    frames.push_back(frame);
  }
  ATTEND_WRITE_VIDEO_OR_SKIP(path, frames);
  fs::resize_file(path, fs::file_size(path) / 2);
  SequenceOptions options;
  options.source.video = path;
  options.resize = "native";
  auto source = OpenFrameSource(options);
  EXPECT_EQ(source->info().frame_count, 20);
  StereoFrame frame;
  int delivered = 0;
  const std::string message = ErrorOf<InputError>([&] {
    while (source->Next(&frame)) ++delivered;
  });
  EXPECT_GT(delivered, 3);
  EXPECT_LT(delivered, 20);
  EXPECT_NE(message.find("ends at frame " + std::to_string(delivered) +
                         ", but it announces 20 frames (0..19); the file may be cut short"),
            std::string::npos)
      << message;
  // A range that stops before the cut reads to its end without an error.
  options.last_frame = delivered - 1;
  source = OpenFrameSource(options);
  int read = 0;
  while (source->Next(&frame)) ++read;
  EXPECT_EQ(read, delivered);
}

TEST(Sequence, VideosThatCannotBeOpenedAreBadInput) {
  testing::TempDir dir;
  SequenceOptions options;
  options.source.video = dir.File("missing.avi");
  std::string message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("video " + options.source.video + ": no such file"), std::string::npos)
      << message;

  options = {};
  options.source.left_video = dir.Write("text.avi", "this is not a video");
  options.source.right_video = dir.File("missing.avi");
  message = ErrorOf<InputError>([&] { OpenFrameSource(options); });
  EXPECT_NE(message.find("video " + options.source.left_video + ": cannot be opened"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace attend
