#include "io/frame_record.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

TEST(InputFromWorking, HalfSizeDoublesBoxesAndQuadruplesAreas) {
  // 640x480 computed at 320x240: scale 0.5 per axis.
  EXPECT_EQ(InputFromWorkingBox({10, 20, 30, 40}, 0.5, 0.5, {640, 480}), cv::Rect(20, 40, 60, 80));
  EXPECT_EQ(InputFromWorkingBox({0, 0, 320, 240}, 0.5, 0.5, {640, 480}), cv::Rect(0, 0, 640, 480));
  FrameRecord record;
  record.frame = 7;
  TargetRecord target;
  target.id = 3;
  target.bbox = {10, 20, 30, 40};
  target.area = 1000;
  target.saliency = 0.5;
  target.state = TargetState::kTracked;
  record.targets = {target};
  record.new_ids = {3};
  const FrameRecord input = InputFromWorking(record, 0.5, 0.5, {640, 480});
  ASSERT_EQ(input.targets.size(), 1u);
  EXPECT_EQ(input.frame, 7);
  EXPECT_EQ(input.targets[0].bbox, cv::Rect(20, 40, 60, 80));
  EXPECT_EQ(input.targets[0].area, 4000);
  EXPECT_EQ(input.targets[0].saliency, 0.5);
  EXPECT_EQ(input.targets[0].state, TargetState::kTracked);
  EXPECT_EQ(input.new_ids, std::vector<int>{3});
}

TEST(InputFromWorking, EdgesRoundPerAxisAndStayInTheFrame) {
  // 752x480 at 320x204 (fit): scales 320/752 and 204/480. Edges round to the nearest pixel:
  // x 3 -> 7.05 -> 7, x 3 + 10 = 13 -> 30.55 -> 31; y 5 -> 11.76 -> 12, 5 + 7 = 12 -> 28.2 -> 28.
  const double sx = 320.0 / 752.0, sy = 204.0 / 480.0;
  EXPECT_EQ(InputFromWorkingBox({3, 5, 10, 7}, sx, sy, {752, 480}), cv::Rect(7, 12, 24, 16));
  // The last working column ends at the input's last column.
  EXPECT_EQ(InputFromWorkingBox({319, 203, 1, 1}, sx, sy, {752, 480}), cv::Rect(750, 478, 2, 2));
  // Stretch: different factors per axis (640x480 in 320x320).
  EXPECT_EQ(InputFromWorkingBox({10, 30, 20, 30}, 0.5, 320.0 / 480.0, {640, 480}),
            cv::Rect(20, 45, 40, 45));
  // Native: unchanged.
  EXPECT_EQ(InputFromWorkingBox({1, 2, 3, 4}, 1.0, 1.0, {16, 16}), cv::Rect(1, 2, 3, 4));
}

TEST(InputFromWorking, EnlargedInputKeepsNonEmptyBoxesAndAreas) {
  // 80x60 enlarged to 320x240: a working pixel is a quarter of an input pixel.
  EXPECT_EQ(InputFromWorkingBox({40, 40, 4, 8}, 4.0, 4.0, {80, 60}), cv::Rect(10, 10, 1, 2));
  const cv::Rect one = InputFromWorkingBox({41, 41, 1, 1}, 4.0, 4.0, {80, 60});
  EXPECT_EQ(one.width, 1);
  EXPECT_EQ(one.height, 1);
  const cv::Rect corner = InputFromWorkingBox({319, 239, 1, 1}, 4.0, 4.0, {80, 60});
  EXPECT_EQ(corner, cv::Rect(79, 59, 1, 1));
  FrameRecord record;
  TargetRecord target;
  target.bbox = {41, 41, 1, 1};
  target.area = 1;
  record.targets = {target};
  EXPECT_EQ(InputFromWorking(record, 4.0, 4.0, {80, 60}).targets[0].area, 1);
  // An empty box stays empty.
  EXPECT_TRUE(InputFromWorkingBox({5, 5, 0, 0}, 4.0, 4.0, {80, 60}).empty());
}

// A resumed target's absent frames and a top-down label are written and read back; a target
// without them has neither key (SPEC 3.3: fields may be added).
TEST(FrameRecordJson, AResumedTargetsAbsentFramesAndALabelReadBack) {
  FrameRecord record;
  record.frame = 4;
  TargetRecord resumed;
  resumed.id = 2;
  resumed.bbox = {1, 2, 3, 4};
  resumed.state = TargetState::kResumed;
  resumed.absent_frames = 17;
  resumed.label = "person";
  TargetRecord plain;
  plain.id = 3;
  plain.state = TargetState::kTracked;
  record.targets = {resumed, plain};
  const std::string line = FrameRecordToJson(record);
  EXPECT_NE(line.find("\"state\":\"resumed\""), std::string::npos) << line;
  EXPECT_NE(line.find("\"absent_frames\":17"), std::string::npos) << line;
  EXPECT_NE(line.find("\"label\":\"person\""), std::string::npos) << line;
  EXPECT_EQ(line.find("absent_frames", line.find("\"id\":3")), std::string::npos) << line;
  const testing::TempDir dir;
  const std::string path = dir.Write("frames.jsonl", line + "\n");
  const std::vector<FrameRecord> read = ReadFrameRecords(path);
  ASSERT_EQ(read.size(), 1u);
  ASSERT_EQ(read[0].targets.size(), 2u);
  EXPECT_EQ(read[0].targets[0].state, TargetState::kResumed);
  EXPECT_TRUE(Visible(read[0].targets[0].state));
  EXPECT_EQ(read[0].targets[0].absent_frames, 17);
  EXPECT_EQ(read[0].targets[0].label, "person");
  EXPECT_EQ(read[0].targets[1].absent_frames, 0);
  EXPECT_EQ(read[0].targets[1].label, "");
}

// A frame recorded twice, or out of order, is bad input naming the file and both lines: scored,
// it would count as another frame.
TEST(FrameRecordJson, ADuplicateOrOutOfOrderFrameIsRefusedWithItsLines) {
  auto line = [](int frame) {
    FrameRecord record;
    record.frame = frame;
    return FrameRecordToJson(record) + "\n";
  };
  const testing::TempDir dir;
  const std::string ok = dir.Write("ok.jsonl", line(0) + line(2) + "\n" + line(5));
  EXPECT_EQ(ReadFrameRecords(ok).size(), 3u);
  const std::string twice = dir.Write("twice.jsonl", line(0) + line(1) + line(1) + line(2));
  std::string message = testing::InputErrorOf([&] { ReadFrameRecords(twice); });
  EXPECT_NE(message.find(twice + ":3: frame 1 again (line 2 has it too)"), std::string::npos)
      << message;
  const std::string back = dir.Write("back.jsonl", line(3) + line(4) + line(2));
  message = testing::InputErrorOf([&] { ReadFrameRecords(back); });
  EXPECT_NE(message.find(back + ":3: frame 2 after frame 4 (line 2)"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace attend

namespace attend {
namespace {

// A stereo run's target: its disparity (scaled with the width to input pixels) and position
// read back; a record without them (older runs, monocular runs) reads as before.
TEST(FrameRecordJson, DisparityAndPositionReadBackAndScale) {
  FrameRecord record;
  record.frame = 2;
  TargetRecord target;
  target.id = 1;
  target.bbox = {4, 4, 10, 10};
  target.state = TargetState::kTracked;
  target.disparity_px = 6.25;
  target.disparity_sd_px = 0.5;
  target.has_position = true;
  target.position_m = {0.5, -0.25, 3.0};
  target.position_sd_m = {0.01, 0.02, 0.25};
  TargetRecord plain;
  plain.id = 2;
  record.targets = {target, plain};
  // Half the input width: disparities double.
  const FrameRecord input = InputFromWorking(record, 0.5, 0.5, {640, 480});
  EXPECT_DOUBLE_EQ(input.targets[0].disparity_px, 12.5);
  EXPECT_DOUBLE_EQ(input.targets[0].disparity_sd_px, 1.0);
  const std::string line = FrameRecordToJson(input);
  EXPECT_NE(line.find("\"disparity_px\":12.5"), std::string::npos) << line;
  EXPECT_NE(line.find("\"position_m\":[0.5,-0.25,3.0]"), std::string::npos) << line;
  EXPECT_EQ(line.find("disparity_px", line.find("\"id\":2")), std::string::npos) << line;
  const testing::TempDir dir;
  const std::vector<FrameRecord> read = ReadFrameRecords(dir.Write("frames.jsonl", line + "\n"));
  ASSERT_EQ(read[0].targets.size(), 2u);
  EXPECT_DOUBLE_EQ(read[0].targets[0].disparity_px, 12.5);
  EXPECT_DOUBLE_EQ(read[0].targets[0].disparity_sd_px, 1.0);
  ASSERT_TRUE(read[0].targets[0].has_position);
  EXPECT_DOUBLE_EQ(read[0].targets[0].position_m[2], 3.0);
  EXPECT_DOUBLE_EQ(read[0].targets[0].position_sd_m[2], 0.25);
  EXPECT_FALSE(read[0].targets[1].has_position);
  EXPECT_FALSE(std::isfinite(read[0].targets[1].disparity_px));
}

TEST(FrameRecordJson, AMalformedPositionIsRefusedWithItsLine) {
  const std::string head =
      R"({"frame":0,"targets":[{"id":1,"bbox":[0,0,2,2],"area":4,"saliency":0.1,)"
      R"("state":"tracked","kind":"object","similarity":"hsv",)";
  const std::string tail = R"(}],"new":[],"timings_ms":{}})";
  const testing::TempDir dir;
  for (const std::string& field : {std::string(R"("position_m":[1,2])"),
                                   std::string(R"("position_m":[1,"2",3])"),
                                   std::string(R"("disparity_px":"7")")}) {
    const std::string path = dir.Write("frames.jsonl", head + field + tail + "\n");
    const std::string message = testing::InputErrorOf([&] { ReadFrameRecords(path); });
    EXPECT_NE(message.find("frames.jsonl:1"), std::string::npos) << field << ": " << message;
  }
}

}  // namespace
}  // namespace attend
