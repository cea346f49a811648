#include "io/ground_truth.h"

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

GtObject Object(int frame, int id, cv::Rect2d box, double visible, double disparity,
                const std::string& kind) {
  GtObject object;
  object.frame = frame;
  object.id = id;
  object.box = box;
  object.visible_fraction = visible;
  object.disparity = disparity;
  object.kind = kind;
  return object;
}

TEST(GroundTruth, CsvRoundTripIsExact) {
  testing::TempDir dir;
  // Values without a short decimal form, which only a full-precision writer preserves.
  const std::vector<GtObject> objects = {
      Object(0, 1, {1.0 / 3.0, 2.0 / 7.0, 10.1, 0.1 + 0.2}, 0.7071067811865476, 12.345678901234567,
             "object"),
      Object(0, 2, {0, 0, 0, 0}, 0.0, 0.0, "skin"),  // hidden: an empty box
      Object(41, 7, {319.99999999999994, 1e-9, 123456.789, 1e-300}, 1.0, -0.0, "object"),
  };
  const std::string path = dir.File("objects.csv");
  WriteObjectsCsv(path, objects);
  const std::vector<GtObject> read = ReadObjectsCsv(path);
  ASSERT_EQ(read.size(), objects.size());
  for (size_t i = 0; i < objects.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(read[i].frame, objects[i].frame);
    EXPECT_EQ(read[i].id, objects[i].id);
    EXPECT_EQ(read[i].box.x, objects[i].box.x);
    EXPECT_EQ(read[i].box.y, objects[i].box.y);
    EXPECT_EQ(read[i].box.width, objects[i].box.width);
    EXPECT_EQ(read[i].box.height, objects[i].box.height);
    EXPECT_EQ(read[i].visible_fraction, objects[i].visible_fraction);
    EXPECT_EQ(read[i].disparity, objects[i].disparity);
    EXPECT_EQ(read[i].kind, objects[i].kind);
  }
}

TEST(GroundTruth, WritesTheHeaderLine) {
  testing::TempDir dir;
  const std::string path = dir.File("objects.csv");
  WriteObjectsCsv(path, {});
  EXPECT_TRUE(ReadObjectsCsv(path).empty());
  const std::string text =
      dir.Write("with_rows.csv", std::string(kObjectsCsvHeader) + "\n3,4,1,2,5,6,0.5,7,skin\n");
  const std::vector<GtObject> read = ReadObjectsCsv(text);
  ASSERT_EQ(read.size(), 1u);
  EXPECT_EQ(read[0].frame, 3);
  EXPECT_EQ(read[0].box, cv::Rect2d(1, 2, 5, 6));
  EXPECT_EQ(read[0].kind, "skin");
}

TEST(GroundTruth, MalformedRowsAreBadInputNamingFileAndLine) {
  testing::TempDir dir;
  const std::string header = std::string(kObjectsCsvHeader) + "\n";
  const std::string good = "0,1,1,2,3,4,0.5,8,object\n";
  struct Case {
    std::string row;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"0,1,1,2,3,4,0.5,8\n", ":3: expected 9 fields"},
      {"0,1,one,2,3,4,0.5,8,object\n", ":3: field 'x' is not a number: 'one'"},
      {"1.5,1,1,2,3,4,0.5,8,object\n", ":3: field 'frame' is not an integer"},
      {"-1,1,1,2,3,4,0.5,8,object\n", ":3: frame number out of range: '-1' (must be in 0..1000000)"},
      {"1000001,1,1,2,3,4,0.5,8,object\n", ":3: frame number out of range"},
      {"0,1,1,2,3,4,1.5,8,object\n", ":3: negative size, or visible_fraction"},
      {"0,1,1,2,3,4,0.5,8,dog\n", ":3: kind must be object, skin, car, person or cyclist, got 'dog'"},
      // The same object twice in one frame would be scored as two objects (issue 30).
      {"0,1,5,6,3,4,0.5,8,object\n", ":3: object 1 again in frame 0 (line 2 has it too)"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.Write("objects.csv", header + good + c.row);
    const std::string message = InputErrorOf([&] { ReadObjectsCsv(path); });
    EXPECT_NE(message.find(path + c.expected), std::string::npos) << message;
  }
  const std::string missing = dir.File("missing.csv");
  const std::string message = InputErrorOf([&] { ReadObjectsCsv(missing); });
  EXPECT_NE(message.find(missing + ": the ground-truth file does not exist"), std::string::npos) << message;
}

TEST(GroundTruth, EmptyDisparityIsUnknown) {
  testing::TempDir dir;
  const std::string path = dir.Write(
      "objects.csv", std::string(kObjectsCsvHeader) + "\n0,1,1,2,3,4,0.5,,object\n0,2,5,6,7,8,1,9.5,skin\n");
  const std::vector<GtObject> read = ReadObjectsCsv(path);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_FALSE(read[0].disparity.has_value());
  EXPECT_EQ(read[0].box, cv::Rect2d(1, 2, 3, 4));
  EXPECT_EQ(read[0].kind, "object");
  ASSERT_TRUE(read[1].disparity.has_value());
  EXPECT_EQ(*read[1].disparity, 9.5);
  // A disparity that is there must still be a number.
  const std::string bad = dir.Write("bad.csv", "0,1,1,2,3,4,0.5,far,object\n");
  const std::string message = InputErrorOf([&] { ReadObjectsCsv(bad); });
  EXPECT_NE(message.find(bad + ":1: field 'disparity' is not a number: 'far'"), std::string::npos)
      << message;
}

TEST(GroundTruth, UnknownDisparityRoundTripsAsAnEmptyField) {
  testing::TempDir dir;
  const std::string path = dir.File("objects.csv");
  GtObject unknown = Object(3, 2, {5, 6, 7, 8}, 0.5, 0.0, "skin");
  unknown.disparity.reset();
  WriteObjectsCsv(path, {Object(3, 1, {1, 2, 3, 4}, 1.0, 2.0, "object"), unknown});
  const std::vector<GtObject> read = ReadObjectsCsv(path);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].disparity, std::optional<double>(2.0));
  EXPECT_FALSE(read[1].disparity.has_value());
  EXPECT_EQ(read[1].box, cv::Rect2d(5, 6, 7, 8));
}

TEST(GroundTruth, ReadsCrlfLineEnds) {
  testing::TempDir dir;
  const std::string path =
      dir.Write("objects.csv", std::string(kObjectsCsvHeader) +
                                   "\r\n0,1,1,2,3,4,0.5,8,object\r\n\r\n1,1,2,3,4,5,1,,skin\r\n");
  const std::vector<GtObject> read = ReadObjectsCsv(path);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].frame, 0);
  EXPECT_EQ(read[0].disparity, std::optional<double>(8.0));
  EXPECT_EQ(read[0].kind, "object");  // not "object\r"
  EXPECT_EQ(read[1].frame, 1);
  EXPECT_EQ(read[1].box, cv::Rect2d(2, 3, 4, 5));
  EXPECT_FALSE(read[1].disparity.has_value());
  EXPECT_EQ(read[1].kind, "skin");
  // Line numbers still count CRLF lines: the fourth line here is malformed.
  const std::string bad = dir.Write(
      "bad.csv", std::string(kObjectsCsvHeader) + "\r\n0,1,1,2,3,4,0.5,8,object\r\n\r\n0,1,x,2,3,4,1,,skin\r\n");
  const std::string message = InputErrorOf([&] { ReadObjectsCsv(bad); });
  EXPECT_NE(message.find(bad + ":4: field 'x' is not a number"), std::string::npos) << message;
}

TEST(GroundTruth, FrameStemAndDisparityPath) {
  EXPECT_EQ(FrameStem(0), "000000");
  EXPECT_EQ(FrameStem(42), "000042");
  EXPECT_EQ(FrameStem(1234567), "1234567");
  EXPECT_EQ(GtDisparityPath("data/seq", 7), "data/seq/gt/disparity/000007.pfm");
}

}  // namespace
}  // namespace attend
