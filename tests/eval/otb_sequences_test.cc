// Finding and reading sequences in the OTB layout (eval/otb_sequences.h) on folders written
// here, whose names, boxes, counts and attributes are known.
#include "eval/otb_sequences.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/error_message.h"
#include "tests/support/otb_maker.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::DrawnSquare;
using testing::InputErrorOf;
using testing::MakeOtbSequence;
using testing::TempDir;

const cv::Size kSize(64, 48);

// Empty image files: discovery lists images without decoding them.
void Images(const TempDir& dir, const std::string& folder, int count) {
  fs::create_directories(dir.File(folder + "/img"));
  for (int i = 1; i <= count; ++i) {
    char name[16];
    std::snprintf(name, sizeof(name), "/img/%04d.jpg", i);
    dir.Write(folder + name, "");
  }
}

TEST(OtbSequences, FindsTheSequencesOfAFolderAndNamesThemAsTheToolkit) {
  TempDir dir;
  MakeOtbSequence(dir.File("Walk"), 4, kSize, {{{5, 5}, {2, 0}, 10}});
  // Two targets, one ground-truth file each: Pair-1 and Pair-2.
  MakeOtbSequence(dir.File("Pair"), 4, kSize, {{{5, 5}, {1, 0}, 10}, {{30, 20}, {0, 1}, 12}});
  dir.Write("Pair/attrs.txt", "SV, DEF,FM\r\n");
  Images(dir, "NoTruth", 2);  // img/ without ground truth: skipped with a note
  dir.Write("README.md", "not a sequence");

  std::vector<std::string> notes;
  const std::vector<OtbSequence> sequences = FindOtbSequences(dir.path().string(), &notes);
  ASSERT_EQ(sequences.size(), 3u);
  EXPECT_EQ(sequences[0].name, "Pair-1");
  EXPECT_EQ(sequences[1].name, "Pair-2");
  EXPECT_EQ(sequences[2].name, "Walk");
  EXPECT_EQ(sequences[1].folder_name, "Pair");
  EXPECT_EQ(fs::path(sequences[1].ground_truth).filename(), "groundtruth_rect.2.txt");
  EXPECT_EQ(sequences[0].attributes, (std::vector<std::string>{"SV", "DEF", "FM"}));
  EXPECT_EQ(sequences[1].attributes, sequences[0].attributes);
  EXPECT_TRUE(sequences[2].attributes.empty());
  // Boxes converted to 0-based pixels, one per frame with its image.
  ASSERT_EQ(sequences[1].truth.size(), 4u);
  ASSERT_EQ(sequences[1].images.size(), 4u);
  EXPECT_EQ(sequences[1].truth[3], cv::Rect2d(30, 23, 12, 12));
  EXPECT_EQ(fs::path(sequences[2].images[3]).filename(), "0004.jpg");
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("NoTruth"), std::string::npos) << notes[0];

  // A sequence folder given itself, with a trailing slash.
  const std::vector<OtbSequence> one = FindOtbSequences(dir.File("Walk") + "/");
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].name, "Walk");
}

TEST(OtbSequences, ReadsEveryDelimiterAndLineEndOfTheBenchmarksFiles) {
  TempDir dir;
  Images(dir, "Comma", 3);
  dir.Write("Comma/groundtruth_rect.txt", "1,2,10,20\n2,3,10,20\n3,4,10,20\n");
  Images(dir, "Crlf", 3);
  dir.Write("Crlf/groundtruth_rect.txt", "1\t2\t10\t20\r\n2\t3\t10\t20\r\n3\t4\t10\t20\r\n");
  Images(dir, "Space", 3);
  dir.Write("Space/groundtruth_rect.txt", "1 2 10 20\n2 3 10 20\n3  4  10  20");
  for (const OtbSequence& sequence : FindOtbSequences(dir.path().string())) {
    ASSERT_EQ(sequence.truth.size(), 3u) << sequence.name;
    EXPECT_EQ(sequence.truth[2], cv::Rect2d(2, 3, 10, 20)) << sequence.name;
    EXPECT_TRUE(sequence.notes.empty()) << sequence.name;
  }
}

TEST(OtbSequences, ScoresTheFramesThatHaveBothAnImageAndABox) {
  TempDir dir;
  // One box more than images, then one image more than boxes: the shorter decides, with a note.
  Images(dir, "Long", 3);
  dir.Write("Long/groundtruth_rect.txt", "1,1,5,5\n1,1,5,5\n1,1,5,5\n1,1,5,5\n");
  Images(dir, "Short", 4);
  dir.Write("Short/groundtruth_rect.txt", "1,1,5,5\n1,1,5,5\n1,1,5,5\n");
  const std::vector<OtbSequence> sequences = FindOtbSequences(dir.path().string());
  ASSERT_EQ(sequences.size(), 2u);
  for (const OtbSequence& sequence : sequences) {
    EXPECT_EQ(sequence.images.size(), 3u) << sequence.name;
    EXPECT_EQ(sequence.truth.size(), 3u) << sequence.name;
    ASSERT_EQ(sequence.notes.size(), 1u) << sequence.name;
  }
  EXPECT_NE(sequences[0].notes[0].find("3 images, 4 boxes"), std::string::npos)
      << sequences[0].notes[0];
}

TEST(OtbSequences, CfgJsonGivesTheRangeAndTheAttributes) {
  TempDir dir;
  Images(dir, "Late", 6);
  // Frames 3..5 of img/ (1-based), the ground truth's lines 1..3.
  dir.Write("Late/groundtruth_rect.txt", "1,1,5,5\n2,1,5,5\n3,1,5,5\n");
  dir.Write("Late/cfg.json",
            R"({"name": "Late", "startFrame": 3, "endFrame": 5, "attributes": ["occ", "IV"]})");
  const std::vector<OtbSequence> sequences = FindOtbSequences(dir.File("Late"));
  ASSERT_EQ(sequences.size(), 1u);
  const OtbSequence& late = sequences[0];
  EXPECT_EQ(late.first_image, 2);
  ASSERT_EQ(late.images.size(), 3u);
  EXPECT_EQ(fs::path(late.images[0]).filename(), "0003.jpg");
  EXPECT_EQ(late.truth[2].x, 2.0);
  EXPECT_EQ(late.attributes, (std::vector<std::string>{"OCC", "IV"}));
  EXPECT_TRUE(late.notes.empty());
  // attrs.txt, where present, is the one read.
  dir.Write("Late/attrs.txt", "BC");
  EXPECT_EQ(FindOtbSequences(dir.File("Late"))[0].attributes, (std::vector<std::string>{"BC"}));
}

TEST(OtbSequences, BadInputNamesTheFolderFileAndLine) {
  TempDir dir;
  EXPECT_NE(InputErrorOf([&] { FindOtbSequences(dir.File("missing")); }).find("no such folder"),
            std::string::npos);
  dir.Write("notes.txt", "nothing here");
  EXPECT_NE(InputErrorOf([&] { FindOtbSequences(dir.path().string()); }).find("no OTB sequence"),
            std::string::npos);

  Images(dir, "Bad", 3);
  dir.Write("Bad/groundtruth_rect.txt", "1,1,5,5\n1,1,five,5\n1,1,5,5\n");
  const std::string line = InputErrorOf([&] { FindOtbSequences(dir.path().string()); });
  EXPECT_NE(line.find("Bad/groundtruth_rect.txt:2"), std::string::npos) << line;

  dir.Write("Bad/groundtruth_rect.txt", "0,0,0,0\n1,1,5,5\n1,1,5,5\n");
  const std::string empty = InputErrorOf([&] { FindOtbSequences(dir.File("Bad")); });
  EXPECT_NE(empty.find("groundtruth_rect.txt:1: no box on the first frame"), std::string::npos)
      << empty;

  dir.Write("Bad/groundtruth_rect.txt", "1,1,5,5\n");
  dir.Write("Bad/cfg.json", R"({"startFrame": 9})");
  const std::string start = InputErrorOf([&] { FindOtbSequences(dir.File("Bad")); });
  EXPECT_NE(start.find("cfg.json: startFrame 9 is beyond the 3 images"), std::string::npos)
      << start;
  dir.Write("Bad/cfg.json", R"({"startFrame": "one"})");
  EXPECT_NE(InputErrorOf([&] { FindOtbSequences(dir.File("Bad")); }).find("startFrame must be"),
            std::string::npos);
  dir.Write("Bad/cfg.json", "{not json");
  EXPECT_NE(InputErrorOf([&] { FindOtbSequences(dir.File("Bad")); }).find("not valid JSON"),
            std::string::npos);
}

TEST(OtbSequences, AttributesHaveTheBenchmarksNamesAndOrder) {
  EXPECT_EQ(OtbAttributeName("SV"), "Scale Variation");
  EXPECT_EQ(OtbAttributeName("OPR"), "Out-of-Plane Rotation");
  EXPECT_EQ(OtbAttributeName("XYZ"), "XYZ");
  std::vector<std::string> codes = {"ZZ", "BC", "IV", "AA", "OCC"};
  std::sort(codes.begin(), codes.end(), OtbAttributeBefore);
  EXPECT_EQ(codes, (std::vector<std::string>{"IV", "OCC", "BC", "AA", "ZZ"}));
}

}  // namespace
}  // namespace attend
