#include "io/ground_truth.h"

#include <gtest/gtest.h>

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
      {"0,1,1,2,3,4,1.5,8,object\n", ":3: negative frame or size, or visible_fraction"},
      {"0,1,1,2,3,4,0.5,8,person\n", ":3: kind must be object or skin, got 'person'"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.Write("objects.csv", header + good + c.row);
    const std::string message = InputErrorOf([&] { ReadObjectsCsv(path); });
    EXPECT_NE(message.find(path + c.expected), std::string::npos) << message;
  }
  const std::string missing = dir.File("missing.csv");
  const std::string message = InputErrorOf([&] { ReadObjectsCsv(missing); });
  EXPECT_NE(message.find(missing + ": cannot read"), std::string::npos) << message;
}

TEST(GroundTruth, FrameStemAndDisparityPath) {
  EXPECT_EQ(FrameStem(0), "000000");
  EXPECT_EQ(FrameStem(42), "000042");
  EXPECT_EQ(FrameStem(1234567), "1234567");
  EXPECT_EQ(GtDisparityPath("data/seq", 7), "data/seq/gt/disparity/000007.pfm");
}

}  // namespace
}  // namespace attend
