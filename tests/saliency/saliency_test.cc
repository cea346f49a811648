#include "saliency/normalisation.h"
#include "saliency/saliency.h"
#include "saliency/saliency_stage.h"
#include "util/error.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

cv::Mat Row(std::initializer_list<float> values) {
  return cv::Mat(std::vector<float>(values), true).reshape(1, 1);
}

TEST(Saliency, MinMaxMapsTheRangeOntoUnit) {
  cv::Mat out;
  NormaliseMap(Row({2.f, 4.f, 6.f, 3.f}), {}, &out);
  EXPECT_FLOAT_EQ(out.at<float>(0), 0.f);
  EXPECT_FLOAT_EQ(out.at<float>(1), 0.5f);
  EXPECT_FLOAT_EQ(out.at<float>(2), 1.f);
  EXPECT_FLOAT_EQ(out.at<float>(3), 0.25f);
}

TEST(Saliency, ConstantMapBecomesZero) {
  cv::Mat out;
  NormaliseMap(cv::Mat(5, 7, CV_32FC1, cv::Scalar(3.5f)), {}, &out);
  EXPECT_EQ(out.size(), cv::Size(7, 5));
  EXPECT_EQ(cv::countNonZero(out), 0);
}

// Peaks drawn as single pixels (or plateaus) on a zero map, far apart.
cv::Mat Peaks(const std::vector<std::pair<cv::Rect, float>>& peaks) {
  cv::Mat map(60, 80, CV_32FC1, cv::Scalar(0.f));
  for (const auto& [box, value] : peaks) map(box).setTo(value);
  return map;
}

TEST(Saliency, LocalMaximaKeepsASinglePeak) {
  SaliencyOptions options;
  options.normalisation = "local_maxima";
  cv::Mat out;
  NormaliseMap(Peaks({{{10, 10, 5, 5}, 8.f}}), options, &out);
  EXPECT_FLOAT_EQ(out.at<float>(12, 12), 1.f);
  EXPECT_EQ(cv::countNonZero(out), 25);
}

TEST(Saliency, LocalMaximaScalesByTheOtherPeaks) {
  SaliencyOptions options;
  options.normalisation = "local_maxima";
  options.local_maxima_window = 5;
  cv::Mat out;
  // Global peak 4 (a plateau counted once), others 2 and 1: after min-max 0.5 and 0.25, mean
  // 0.375, factor (1 - 0.375)^2.
  NormaliseMap(Peaks({{{5, 5, 10, 10}, 4.f}, {{40, 10, 1, 1}, 2.f}, {{60, 40, 3, 2}, 1.f}}),
               options, &out);
  const float factor = 0.625f * 0.625f;
  EXPECT_NEAR(out.at<float>(7, 7), factor, 1e-6);
  EXPECT_NEAR(out.at<float>(10, 40), 0.5f * factor, 1e-6);
  EXPECT_NEAR(out.at<float>(40, 61), 0.25f * factor, 1e-6);
}

TEST(Saliency, LocalMaximaSuppressesTwoEqualPeaks) {
  SaliencyOptions options;
  options.normalisation = "local_maxima";
  cv::Mat out;
  NormaliseMap(Peaks({{{5, 5, 3, 3}, 1.f}, {{50, 40, 3, 3}, 1.f}}), options, &out);
  EXPECT_EQ(cv::countNonZero(out), 0);
}

TEST(Saliency, CombineIsTheWeightedMean) {
  const cv::Mat a = Row({0.f, 1.f, 0.5f});
  const cv::Mat b = Row({1.f, 1.f, 0.f});
  cv::Mat out;
  CombineMaps({a, b}, {1.0, 3.0}, a.size(), &out);
  EXPECT_FLOAT_EQ(out.at<float>(0), 0.75f);
  EXPECT_FLOAT_EQ(out.at<float>(1), 1.f);
  EXPECT_FLOAT_EQ(out.at<float>(2), 0.125f);
}

TEST(Saliency, ZeroWeightLeavesNoTrace) {
  const cv::Mat a = Row({0.f, 1.f, 0.5f});
  const cv::Mat b = Row({1.f, 1.f, 0.f});
  cv::Mat alone, with_zero;
  CombineMaps({a}, {2.0}, a.size(), &alone);
  CombineMaps({a, b}, {2.0, 0.0}, a.size(), &with_zero);
  EXPECT_EQ(cv::norm(alone, with_zero, cv::NORM_INF), 0.0);
}

TEST(Saliency, NoWeightGivesZero) {
  cv::Mat out;
  CombineMaps({}, {}, cv::Size(4, 3), &out);
  EXPECT_EQ(out.size(), cv::Size(4, 3));
  EXPECT_EQ(cv::countNonZero(out), 0);
  CombineMaps({Row({1.f, 2.f})}, {0.0}, cv::Size(2, 1), &out);
  EXPECT_EQ(cv::countNonZero(out), 0);
}

TEST(Saliency, OptionsAreChecked) {
  SaliencyOptions options;
  EXPECT_EQ(options.Check(), "");
  options.local_maxima_window = 4;
  EXPECT_NE(options.Check().find("odd"), std::string::npos);
}

// One registry holds the built-in normalisations and the plugins'; a name is taken once.
TEST(Saliency, TheRegistryHoldsTheBuiltInNormalisationsAndRefusesATakenName) {
  NormalisationRegistry registry;
  EXPECT_EQ(registry.Names(), (std::vector<std::string>{"minmax", "local_maxima"}));
  EXPECT_EQ(registry.Find("itti"), nullptr);
  ASSERT_NE(registry.Find("minmax"), nullptr);
  EXPECT_TRUE(registry.Find("minmax")->built_in);
  const auto half = [](const cv::Mat& map, cv::Mat* out) { *out = cv::Mat(map.size(), CV_32FC1, 0.5f); };
  registry.Add("half", "every pixel 0.5", "libhalf.so", half);
  EXPECT_EQ(registry.Names(), (std::vector<std::string>{"minmax", "local_maxima", "half"}));
  try {
    registry.Add("minmax", "", "libclash.so", half);
    ADD_FAILURE() << "a built-in name was taken again";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("libclash.so"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("is built in"), std::string::npos) << e.what();
  }
  EXPECT_THROW(registry.Add("half", "", "libother.so", half), ConfigError);
}

// The stage normalises each map by its own normalisation or the default one, and on a grey
// frame a constant map weighs 0: a map 0..1 and a constant one combine to the first at half
// weight on a colour frame, and to the first alone on a grey frame.
TEST(Saliency, TheStageWeighsAConstantMapZeroOnAGreyFrame) {
  NormalisationRegistry registry;
  SaliencyInput ramp{"ramp", 1.0, {}};
  SaliencyInput flat{"flat", 1.0, {}};
  SaliencyStage stage(SaliencyOptions(), *registry.Find("minmax"), {ramp, flat});
  const cv::Mat a = Row({0.f, 2.f, 4.f}), b = Row({3.f, 3.f, 3.f});
  stage.Combine({&a, &b}, false, a.size());
  EXPECT_NEAR(stage.saliency().at<float>(0, 2), 0.5f, 1e-6);
  EXPECT_EQ(stage.weights(), (std::vector<double>{1.0, 1.0}));
  stage.Combine({&a, &b}, true, a.size());
  EXPECT_NEAR(stage.saliency().at<float>(0, 1), 0.5f, 1e-6);
  EXPECT_NEAR(stage.saliency().at<float>(0, 2), 1.0f, 1e-6);
  EXPECT_EQ(stage.weights(), (std::vector<double>{1.0, 0.0}));

  // A plugin's normalisation that leaves [0, 1] is a configuration error naming the feature.
  registry.Add("two", "", "libtwo.so",
               [](const cv::Mat& map, cv::Mat* out) { *out = cv::Mat(map.size(), CV_32FC1, 2.f); });
  SaliencyInput broken{"broken", 1.0, *registry.Find("two")};
  SaliencyStage bad(SaliencyOptions(), *registry.Find("minmax"), {broken});
  try {
    bad.Combine({&a}, false, a.size());
    ADD_FAILURE() << "values outside [0, 1] were accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'broken' (libtwo.so)"), std::string::npos) << e.what();
  }
}

TEST(Saliency, ProductIsTheWeightedGeometricMeanAndAZeroVetoes) {
  cv::Mat out;
  MultiplyMaps({Row({1.f, 0.25f, 1.f}), Row({1.f, 1.f, 0.f})}, {1.0, 1.0}, {}, cv::Size(3, 1), &out);
  EXPECT_NEAR(out.at<float>(0), 1.f, 1e-5);  // (1.01 x 1.01)^(1/2) - 0.01
  EXPECT_NEAR(out.at<float>(1), std::sqrt(0.26f * 1.01f) - 0.01f, 1e-5);
  // Where one map is 0 the product is near 0, the sum would be 0.5.
  EXPECT_LT(out.at<float>(2), 0.1f);
  CombineMaps({Row({1.f, 0.25f, 1.f}), Row({1.f, 1.f, 0.f})}, {1.0, 1.0}, cv::Size(3, 1), &out);
  EXPECT_FLOAT_EQ(out.at<float>(2), 0.5f);
}

TEST(Saliency, AnAdditiveMapIsAddedToTheProductOfTheOthers) {
  cv::Mat out;
  // Weights 1, 1 (factors) and 2 (added): (2 G + 2 n) / 4, G the geometric mean of the first two.
  const cv::Mat a = Row({1.f, 0.25f, 1.f, 0.f});
  const cv::Mat b = Row({1.f, 1.f, 0.f, 0.f});
  const cv::Mat faces = Row({0.f, 0.f, 0.f, 1.f});
  MultiplyMaps({a, b, faces}, {1.0, 1.0, 2.0}, {false, false, true}, cv::Size(4, 1), &out);
  EXPECT_NEAR(out.at<float>(0), 0.5f, 1e-5);
  EXPECT_NEAR(out.at<float>(1), 0.5f * (std::sqrt(0.26f * 1.01f) - 0.01f), 1e-5);
  EXPECT_NEAR(out.at<float>(2), 0.5f * (std::sqrt(1.01f * 0.01f) - 0.01f), 1e-5);  // a veto
  // Where the others veto, the added map still counts in full: no veto on it.
  EXPECT_NEAR(out.at<float>(3), 0.5f, 1e-5);
  // An added map that is 0 everywhere scales the product uniformly: the same map up to a factor.
  cv::Mat alone, with_empty;
  MultiplyMaps({a, b}, {1.0, 1.0}, {}, cv::Size(4, 1), &alone);
  MultiplyMaps({a, b, cv::Mat::zeros(1, 4, CV_32FC1)}, {1.0, 1.0, 2.0}, {false, false, true},
               cv::Size(4, 1), &with_empty);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(with_empty.at<float>(i), 0.5f * alone.at<float>(i), 1e-6);
  // Only added maps: their weighted mean, as the sum would give.
  MultiplyMaps({a, b}, {1.0, 3.0}, {true, true}, cv::Size(4, 1), &out);
  EXPECT_NEAR(out.at<float>(1), (0.25f + 3.f) / 4.f, 1e-6);
}

TEST(Saliency, GammaRaisesTheMapToItsPowerAfterTheBlur) {
  cv::Mat map = Row({0.f, 0.25f, 0.5f, 1.f});
  SaliencyOptions options;
  options.gamma = 2.0;
  SmoothSaliency(options, &map);
  EXPECT_FLOAT_EQ(map.at<float>(0), 0.f);
  EXPECT_FLOAT_EQ(map.at<float>(1), 0.0625f);
  EXPECT_FLOAT_EQ(map.at<float>(2), 0.25f);
  EXPECT_FLOAT_EQ(map.at<float>(3), 1.f);
  // A map whose maximum is 0.5 is scaled to 1 first: the same shape on every image.
  map = Row({0.f, 0.125f, 0.25f, 0.5f});
  SmoothSaliency(options, &map);
  EXPECT_FLOAT_EQ(map.at<float>(1), 0.0625f);
  EXPECT_FLOAT_EQ(map.at<float>(3), 1.f);
}

TEST(Saliency, BlurSpreadsAPeakAndKeepsItsHeight) {
  cv::Mat map(40, 40, CV_32FC1, cv::Scalar(0.f));
  map.at<float>(20, 20) = 0.8f;
  SaliencyOptions options;
  SmoothSaliency(options, &map);  // blur 0: unchanged
  EXPECT_EQ(cv::countNonZero(map), 1);
  options.blur = 0.05;  // sigma 2 px
  SmoothSaliency(options, &map);
  double high = 0.0;
  cv::Point at;
  cv::minMaxLoc(map, nullptr, &high, nullptr, &at);
  EXPECT_NEAR(high, 0.8, 1e-5);
  EXPECT_EQ(at, cv::Point(20, 20));
  EXPECT_GT(map.at<float>(20, 22), 0.2f);  // exp(-1/2) x 0.8 two px away
}

// The built-in normalisations are one table: the option's names, the registry and NormaliseMap
// all follow it.
TEST(NormalisationRegistry, TheBuiltInOnesComeFromOneTable) {
  const std::vector<BuiltinNormalisation>& table = BuiltinNormalisations();
  ASSERT_GE(table.size(), 2u);
  EXPECT_EQ(std::string(table.front().name), "minmax");  // the default comes first
  const NormalisationRegistry registry;
  std::vector<std::string> names;
  for (const BuiltinNormalisation& row : table) {
    names.push_back(row.name);
    const NormalisationRegistry::Entry* entry = registry.Find(row.name);
    ASSERT_NE(entry, nullptr) << row.name;
    EXPECT_TRUE(entry->built_in);
    EXPECT_EQ(entry->summary, row.summary);
    // The registry's entry, NormaliseMap by name and the row's function give the same map.
    const cv::Mat map = Row({1.f, 5.f, 2.f, 5.f, 0.f, 3.f});
    SaliencyOptions options;
    options.normalisation = row.name;
    options.local_maxima_window = 3;
    cv::Mat by_row, by_entry, by_name;
    row.normalise(map, options, &by_row);
    entry->normalise(map, options, &by_entry);
    NormaliseMap(map, options, &by_name);
    EXPECT_EQ(cv::norm(by_row, by_entry, cv::NORM_INF), 0.0) << row.name;
    EXPECT_EQ(cv::norm(by_row, by_name, cv::NORM_INF), 0.0) << row.name;
  }
  EXPECT_EQ(SaliencyOptions::Normalisations(), names);
  EXPECT_EQ(registry.Names(), names);
}

}  // namespace
}  // namespace attend
