// attend eval prints the MOTChallenge measures (SPEC 4) at IoU 0.5 and 0.3 beside its own
// scores: a run folder written by attend run whose frames.jsonl is replaced by records built
// here, scored against ground truth whose answers are worked out by hand.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/ground_truth.h"
#include "io/frame_record.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::Attend;
using testing::Result;

constexpr double kTolerance = 1e-12;

TEST(EvalMotCli, PrintsBothMotBlocksAfterTheExistingKeys) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 3, 64, 48);
  Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;

  // Person A under target 1 in every frame; person B under target 2, which covers only its
  // upper 16 of 40 rows (IoU 0.4): a match at 0.3, not at 0.5.
  const cv::Rect2d person_a(4, 4, 20, 40), person_b(36, 4, 20, 40);
  std::vector<GtObject> truth;
  std::string records;
  for (int f = 0; f < 3; ++f) {
    for (const auto& [id, box] : {std::pair{1, person_a}, std::pair{2, person_b}}) {
      GtObject object;
      object.frame = f;
      object.id = id;
      object.box = box;
      object.visible_fraction = 1.0;
      truth.push_back(object);
    }
    FrameRecord record;
    record.frame = f;
    const TargetState state = f == 0 ? TargetState::kNew : TargetState::kTracked;
    TargetRecord a, b;
    a.id = 1, a.bbox = cv::Rect(4, 4, 20, 40), a.area = 800, a.state = state;
    b.id = 2, b.bbox = cv::Rect(36, 4, 20, 16), b.area = 320, b.state = state;
    record.targets = {a, b};
    if (f == 0) record.new_ids = {1, 2};
    records += FrameRecordToJson(record) + "\n";
  }
  dir.Write("run/frames.jsonl", records);
  std::filesystem::create_directories(dir.File("seq/gt"));
  WriteObjectsCsv(dir.File("seq/gt/objects.csv"), truth);

  r = Attend(dir, {"eval", "run", "--gt", "seq/gt"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::ordered_json report = nlohmann::ordered_json::parse(r.out);
  std::vector<std::string> keys;
  for (const auto& [key, value] : report.items()) keys.push_back(key);
  EXPECT_EQ(keys, (std::vector<std::string>{"run", "gt", "frames", "objects", "attended",
                                            "coverage", "mean_latency", "revisits",
                                            "identity_switches", "mean_iou", "mot", "per_object"}));
  EXPECT_EQ(report["coverage"], 1.0);  // today's score, at 0.3, unchanged

  const nlohmann::ordered_json& mot = report["mot"];
  ASSERT_TRUE(mot.contains("iou_0.5")) << mot.dump();
  ASSERT_TRUE(mot.contains("iou_0.3")) << mot.dump();
  // At 0.5: GT 6, A matched 3 times, B missed 3 times and target 2 a false positive 3 times;
  // MOTA = 1 - 6/6; identity: IDTP 3 (A with 1), IDFP 3, IDFN 3, IDF1 0.5.
  const nlohmann::ordered_json& strict = mot["iou_0.5"];
  EXPECT_EQ(strict["match_iou"], 0.5);
  EXPECT_EQ(strict["objects"], 2);
  EXPECT_EQ(strict["GT"], 6);
  EXPECT_EQ(strict["FN"], 3);
  EXPECT_EQ(strict["FP"], 3);
  EXPECT_EQ(strict["IDSW"], 0);
  EXPECT_NEAR(strict["MOTA"].get<double>(), 0.0, kTolerance);
  EXPECT_NEAR(strict["MOTP"].get<double>(), 1.0, kTolerance);
  EXPECT_NEAR(strict["IDF1"].get<double>(), 0.5, kTolerance);
  EXPECT_EQ(strict["objects_attended_whole"], 1);
  EXPECT_NEAR(strict["attended_whole_fraction"].get<double>(), 0.5, kTolerance);
  EXPECT_EQ(strict["targets_started"], 2);
  EXPECT_EQ(strict["MT"], 1);
  EXPECT_EQ(strict["ML"], 1);
  // At 0.3 both are matched: MOTA 1, IDF1 1, MOTP = (3 x 1 + 3 x 0.4) / 6 = 0.7.
  const nlohmann::ordered_json& loose = mot["iou_0.3"];
  EXPECT_EQ(loose["match_iou"], 0.3);
  EXPECT_EQ(loose["FN"], 0);
  EXPECT_EQ(loose["FP"], 0);
  EXPECT_NEAR(loose["MOTA"].get<double>(), 1.0, kTolerance);
  EXPECT_NEAR(loose["MOTP"].get<double>(), 0.7, kTolerance);
  EXPECT_NEAR(loose["IDF1"].get<double>(), 1.0, kTolerance);
  EXPECT_EQ(loose["objects_attended_whole"], 2);
  EXPECT_NEAR(loose["ids_per_attended_object"].get<double>(), 1.0, kTolerance);
  EXPECT_NEAR(loose["purity"].get<double>(), 1.0, kTolerance);
}

}  // namespace
}  // namespace attend
