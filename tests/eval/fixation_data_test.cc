#include "eval/fixation_data.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/fixation_metrics.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::InputErrorOf;
using testing::TempDir;

TEST(ReadFixationFile, ReadsDataLinesAndConvertsToZeroBased) {
  TempDir dir;
  const std::string path = dir.Write("f.txt",
                                     "# subject x y onset duration\n"
                                     "\n"
                                     "0 1 1\n"
                                     "   # an indented comment\n"
                                     "3\t10.5  20.25 0.3 0.1 extra\n"
                                     "  \t \n"
                                     "12 256 1e2\r\n");
  const std::vector<Fixation> fixations = ReadFixationFile(path);
  ASSERT_EQ(fixations.size(), 3u);
  EXPECT_EQ(fixations[0].subject, 0);
  EXPECT_DOUBLE_EQ(fixations[0].x, 0.0);  // the file's first pixel is (1, 1)
  EXPECT_DOUBLE_EQ(fixations[0].y, 0.0);
  EXPECT_EQ(fixations[1].subject, 3);
  EXPECT_DOUBLE_EQ(fixations[1].x, 9.5);
  EXPECT_DOUBLE_EQ(fixations[1].y, 19.25);
  EXPECT_EQ(fixations[2].subject, 12);
  EXPECT_DOUBLE_EQ(fixations[2].x, 255.0);
  EXPECT_DOUBLE_EQ(fixations[2].y, 99.0);
}

TEST(ReadFixationFile, EmptyFileHasNoFixations) {
  TempDir dir;
  EXPECT_TRUE(ReadFixationFile(dir.Write("f.txt", "# only a comment\n")).empty());
}

// The message of the error a file whose line 3 is `bad` gives.
std::string ErrorForThirdLine(const TempDir& dir, const std::string& bad) {
  const std::string path = dir.Write("bad.txt", "# header\n0 5 5\n" + bad + "\n1 2 3\n");
  return InputErrorOf([&] { ReadFixationFile(path); });
}

TEST(ReadFixationFile, BadLinesNameThePathAndLine) {
  TempDir dir;
  const std::string where = dir.File("bad.txt") + ":3: ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"0 5", "got 2 column(s)"},
      {"zero 5 5", "subject 'zero' is not an integer"},
      {"1.5 5 5", "subject '1.5' is not an integer"},
      {"-1 5 5", "subject -1 is negative"},
      {"0 five 5", "x 'five' is not a number"},
      {"0 5 5px", "y '5px' is not a number"},
      {"0 inf 5", "x 'inf' is not finite"},
      {"0 5 nan", "y 'nan' is not finite"},
  };
  for (const auto& [line, problem] : cases) {
    const std::string message = ErrorForThirdLine(dir, line);
    EXPECT_EQ(message.rfind(where, 0), 0u) << line << " -> " << message;
    EXPECT_NE(message.find(problem), std::string::npos) << line << " -> " << message;
  }
}

TEST(ReadFixationFile, BadInputMapsToTheBadInputExitStatus) {
  TempDir dir;
  const std::string path = dir.Write("bad.txt", "0 1\n");
  try {
    ReadFixationFile(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), ExitStatus::kBadInput);
    EXPECT_NE(std::string(e.what()).find(path + ":1:"), std::string::npos) << e.what();
  }
}

TEST(ReadFixationFile, DurationsComeFromTheColumnTheHeaderNames) {
  TempDir dir;
  const DurationColumn header{DurationColumn::Source::kHeader};
  // crowd200's layout: milliseconds in the 4th column.
  const std::string crowd = dir.Write("crowd.txt",
                                      "# subject x y duration_ms  (viewing order)\n"
                                      "0 10 20 250\n"
                                      "1 11 21 120.5\n");
  std::vector<Fixation> fixations = ReadFixationFile(crowd, header);
  ASSERT_EQ(fixations.size(), 2u);
  EXPECT_DOUBLE_EQ(fixations[0].duration_s, 0.25);
  EXPECT_DOUBLE_EQ(fixations[1].duration_s, 0.1205);
  // NUS Scene500's: seconds in the 5th, after the onset.
  const std::string nus = dir.Write("nus.txt",
                                    "# subject_index(0-based) x_col_px y_row_px onset_s duration_s\n"
                                    "0 49.78 118.47 0.334 0.134\n");
  fixations = ReadFixationFile(nus, header);
  ASSERT_EQ(fixations.size(), 1u);
  EXPECT_DOUBLE_EQ(fixations[0].duration_s, 0.134);
  // No header naming a duration: durations unknown. Without asking: unknown too.
  EXPECT_DOUBLE_EQ(ReadFixationFile(dir.Write("plain.txt", "# subject x y\n0 1 1 5\n"), header)[0]
                       .duration_s,
                   -1.0);
  EXPECT_DOUBLE_EQ(ReadFixationFile(crowd)[0].duration_s, -1.0);
  // A given column overrides the header: the 4th column read as seconds.
  const DurationColumn given{DurationColumn::Source::kColumn, 3, 1.0};
  EXPECT_DOUBLE_EQ(ReadFixationFile(crowd, given)[0].duration_s, 250.0);
}

TEST(ReadFixationFile, BadDurationsNameThePathAndLine) {
  TempDir dir;
  const DurationColumn header{DurationColumn::Source::kHeader};
  const std::string missing = dir.Write("m.txt", "# subject x y duration_ms\n0 1 1 200\n0 2 2\n");
  EXPECT_NE(InputErrorOf([&] { ReadFixationFile(missing, header); }).find("m.txt:3: no duration"),
            std::string::npos);
  const std::string negative = dir.Write("n.txt", "# subject x y duration_ms\n0 1 1 -5\n");
  EXPECT_NE(InputErrorOf([&] { ReadFixationFile(negative, header); }).find("n.txt:2: duration -5"),
            std::string::npos);
  const std::string text = dir.Write("t.txt", "# subject x y duration_ms\n0 1 1 long\n");
  EXPECT_NE(InputErrorOf([&] { ReadFixationFile(text, header); }).find("t.txt:2: duration 'long'"),
            std::string::npos);
  const std::string clash = dir.Write("c.txt", "# duration_ms x y\n0 1 1\n");
  EXPECT_NE(InputErrorOf([&] { ReadFixationFile(clash, header); }).find("c.txt:1"),
            std::string::npos);
}

TEST(GroupBySubject, KeepsEachSubjectsViewingOrder) {
  TempDir dir;
  const std::string path = dir.Write("f.txt", "2 1 1\n0 5 5\n2 2 2\n0 6 6\n2 3 3\n");
  const std::vector<SubjectFixations> groups = GroupBySubject(ReadFixationFile(path));
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].subject, 0);
  ASSERT_EQ(groups[0].fixations.size(), 2u);
  EXPECT_DOUBLE_EQ(groups[0].fixations[0].x, 4.0);
  EXPECT_DOUBLE_EQ(groups[0].fixations[1].x, 5.0);
  EXPECT_EQ(groups[1].subject, 2);
  ASSERT_EQ(groups[1].fixations.size(), 3u);
  EXPECT_DOUBLE_EQ(groups[1].fixations[2].x, 2.0);
}

TEST(ReadFixationFile, UnreadableFileNamesThePath) {
  TempDir dir;
  const std::string path = dir.File("missing.txt");
  EXPECT_NE(InputErrorOf([&] { ReadFixationFile(path); }).find(path), std::string::npos);
  const std::string folder = dir.path().string();
  EXPECT_NE(InputErrorOf([&] { ReadFixationFile(folder); }).find(folder), std::string::npos);
}

// A tiny stimulus image at DIR/stimuli/name.
void WriteStimulus(const TempDir& dir, const std::string& name) {
  std::filesystem::create_directories(dir.path() / "stimuli");
  ASSERT_TRUE(cv::imwrite(dir.File("stimuli/" + name), cv::Mat(4, 6, CV_8UC3, cv::Scalar::all(9))));
}

TEST(OpenFixationDataset, KeepsStimuliWithFixationsAndCountsTheRest) {
  TempDir dir;
  WriteStimulus(dir, "b.png");
  WriteStimulus(dir, "a.jpg");
  dir.Write("stimuli/notes.md", "not a stimulus");
  dir.Write("fixations/b.txt", "0 1 1\n");
  const FixationDataset dataset = OpenFixationDataset(dir.path().string());
  ASSERT_EQ(dataset.items.size(), 1u);
  EXPECT_EQ(dataset.items[0].id, "b");
  EXPECT_EQ(dataset.items[0].stimulus_path, dir.File("stimuli/b.png"));
  EXPECT_EQ(dataset.items[0].fixations_path, dir.File("fixations/b.txt"));
  EXPECT_EQ(dataset.skipped, 1);
}

TEST(OpenFixationDataset, SortsByIdAndCountsOrphanFixationFiles) {
  TempDir dir;
  WriteStimulus(dir, "c.png");
  WriteStimulus(dir, "a.bmp");
  dir.Write("fixations/c.txt", "0 1 1\n");
  dir.Write("fixations/a.txt", "0 1 1\n");
  dir.Write("fixations/z.txt", "0 1 1\n");
  const FixationDataset dataset = OpenFixationDataset(dir.path().string());
  ASSERT_EQ(dataset.items.size(), 2u);
  EXPECT_EQ(dataset.items[0].id, "a");
  EXPECT_EQ(dataset.items[1].id, "c");
  EXPECT_EQ(dataset.skipped, 1);
}

TEST(OpenFixationDataset, MissingFoldersAreNamed) {
  TempDir dir;
  const std::string root = dir.path().string();
  dir.Write("fixations/a.txt", "0 1 1\n");
  EXPECT_EQ(InputErrorOf([&] { OpenFixationDataset(root); }), root + ": no stimuli/ folder");
  std::filesystem::remove_all(dir.path() / "fixations");
  WriteStimulus(dir, "a.png");
  EXPECT_EQ(InputErrorOf([&] { OpenFixationDataset(root); }), root + ": no fixations/ folder");
  std::filesystem::create_directories(dir.path() / "fixations");
  EXPECT_EQ(InputErrorOf([&] { OpenFixationDataset(root); }),
            root + ": no stimulus has a fixation file");
}

TEST(OpenFixationDataset, TwoStimuliWithOneIdAreAnError) {
  TempDir dir;
  WriteStimulus(dir, "a.png");
  WriteStimulus(dir, "a.jpg");
  dir.Write("fixations/a.txt", "0 1 1\n");
  EXPECT_NE(InputErrorOf([&] { OpenFixationDataset(dir.path().string()); }).find("id a"),
            std::string::npos);
}

// The NUS scene dataset as converted in shared/data: its density maps are Gaussians of about
// one degree (0.025 x the image's larger side) over the fixations.
TEST(FixationDatasetNus, DensityMatchesTheDatasetsDensityMap) {
  const std::string root = testing::SharedData() + "/fixations/nus_scene500";
  if (!std::filesystem::is_directory(root)) GTEST_SKIP() << root << " is absent";
  const FixationDataset dataset = OpenFixationDataset(root);
  EXPECT_EQ(dataset.items.size(), 500u);
  ASSERT_FALSE(dataset.items.empty());
  const FixationItem& item = dataset.items.front();
  EXPECT_EQ(item.id, "001");
  const std::vector<Fixation> fixations = ReadFixationFile(item.fixations_path);
  EXPECT_GT(fixations.size(), 10u);
  const cv::Mat stimulus = cv::imread(item.stimulus_path);
  ASSERT_FALSE(stimulus.empty());
  const cv::Mat truth = cv::imread(root + "/density_maps/001.png", cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(truth.size(), stimulus.size());
  cv::Mat truth_float;
  truth.convertTo(truth_float, CV_32F);
  const double sigma = 0.025 * std::max(stimulus.cols, stimulus.rows);
  const cv::Mat density = FixationDensity(stimulus.size(), fixations, sigma);
  EXPECT_GT(Cc(truth_float, density), 0.99);
  // And the dataset's own maps score as a good saliency model should.
  EXPECT_GT(AucJudd(truth_float, fixations), 0.8);
  EXPECT_GT(Nss(truth_float, fixations), 1.0);
}

}  // namespace
}  // namespace attend
