// Re-identification (semiattentive/reidentification.h): an appearance with an embedding is
// compared by the embeddings' cosine, blended embeddings stay of unit length; with the reference
// data's OSNet, drawn people in other poses are nearer themselves than each other, and what
// cannot be read or run is bad input.
#include "semiattentive/reidentification.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "semiattentive/object_files.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

cv::Mat Unit(std::vector<float> values) {
  cv::Mat vector = cv::Mat(values, true).reshape(1, 1);
  return vector / cv::norm(vector);
}

// An appearance of one grey colour, with `embedding`.
ObjectAppearance Plain(cv::Scalar colour, cv::Mat embedding) {
  const cv::Mat image(40, 20, CV_8UC3, colour);
  ObjectAppearance appearance = ObjectAppearance::Of(image, cv::Mat(), cv::Rect(0, 0, 20, 40));
  appearance.embedding = std::move(embedding);
  return appearance;
}

TEST(Reidentification, TheEmbeddingDecidesTheSimilarityWhenBothHaveOne) {
  // Same colour, embeddings 60 degrees apart: the cosine, 0.5, not the colours' 1.
  const ObjectAppearance a = Plain(cv::Scalar(30, 30, 30), Unit({1.f, 0.f, 0.f}));
  const ObjectAppearance b = Plain(cv::Scalar(30, 30, 30), Unit({0.5f, 0.8660254f, 0.f}));
  EXPECT_NEAR(a.Similarity(b), 0.5, 1e-5);
  // Opposite embeddings clip at 0.
  EXPECT_EQ(a.Similarity(Plain(cv::Scalar(30, 30, 30), Unit({-1.f, 0.f, 0.f}))), 0.0);
  // One without: the model-free similarity (the same colour, plain: 1).
  EXPECT_NEAR(a.Similarity(Plain(cv::Scalar(30, 30, 30), cv::Mat())), 1.0, 1e-6);
}

TEST(Reidentification, BlendedEmbeddingsStayOfUnitLengthAndMoveTowardsWhatWasSeen) {
  ObjectAppearance kept = Plain(cv::Scalar(30, 30, 30), Unit({1.f, 0.f}));
  kept.Blend(Plain(cv::Scalar(30, 30, 30), Unit({0.f, 1.f})), 0.5f);
  EXPECT_NEAR(cv::norm(kept.embedding), 1.0, 1e-6);
  EXPECT_NEAR(kept.embedding.at<float>(0), kept.embedding.at<float>(1), 1e-6);
  // A frame without an embedding keeps the one it has.
  kept.Blend(Plain(cv::Scalar(30, 30, 30), cv::Mat()), 0.5f);
  EXPECT_NEAR(kept.embedding.at<float>(0), std::sqrt(0.5f), 1e-6);
}

TEST(Reidentification, AFileThatIsNotANetworkIsBadInputNamingIt) {
  testing::TempDir dir;
  AppearanceOptions options;
  options.model = dir.Write("osnet.onnx", "not a network\n");
  try {
    Reidentifier::Load(options, "attention.appearance");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), ExitStatus::kBadInput);
    EXPECT_NE(std::string(e.what()).find(options.model), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("attention.appearance"), std::string::npos) << e.what();
  }
}

// A drawn person on a grey street: a head, a shirt and trousers of the given colours, legs
// apart by `stride` px, standing at `x` in a 160 x 160 image, `height` px tall.
cv::Mat Person(cv::Scalar shirt, cv::Scalar trousers, int x, int height, int stride) {
  cv::Mat image(160, 160, CV_8UC3, cv::Scalar(110, 115, 120));
  const int top = 150 - height, unit = height / 8;
  cv::circle(image, cv::Point(x, top + unit), unit, cv::Scalar(120, 150, 200), cv::FILLED);
  cv::rectangle(image, cv::Rect(x - unit, top + 2 * unit, 2 * unit, 3 * unit), shirt, cv::FILLED);
  cv::line(image, cv::Point(x - unit / 2, top + 5 * unit), cv::Point(x - stride, 150), trousers,
           unit);
  cv::line(image, cv::Point(x + unit / 2, top + 5 * unit), cv::Point(x + stride, 150), trousers,
           unit);
  return image;
}

TEST(Reidentification, OsnetFindsADrawnPersonNearerHimselfThanAnother) {
  AppearanceOptions options;
  options.model = testing::SharedData() + "/models/osnet/osnet_x0_25_msmt17.onnx";
  if (!fs::exists(options.model)) GTEST_SKIP() << "no " << options.model << " (reference data)";
  std::unique_ptr<Reidentifier> reid = Reidentifier::Load(options, "attention.appearance");
  EXPECT_EQ(reid->dimensions(), 512);
  const cv::Scalar red(40, 40, 200), blue(200, 60, 30), dark(40, 40, 40), light(200, 200, 190);
  // A in a red shirt and dark trousers, B in a blue shirt and light trousers; A again further
  // right, smaller and mid-stride.
  const cv::Mat a1 = Person(red, dark, 60, 120, 6), a2 = Person(red, dark, 90, 104, 14);
  const cv::Mat b1 = Person(blue, light, 60, 120, 6);
  const auto box = [](int x, int height) {
    return cv::Rect(x - height / 4, 150 - height, height / 2, height);
  };
  const cv::Mat ea1 = reid->Embed(a1, box(60, 120)), ea2 = reid->Embed(a2, box(90, 104));
  const cv::Mat eb1 = reid->Embed(b1, box(60, 120));
  ASSERT_EQ(ea1.cols, 512);
  EXPECT_NEAR(cv::norm(ea1), 1.0, 1e-5);
  EXPECT_GT(EmbeddingSimilarity(ea1, ea2), EmbeddingSimilarity(ea1, eb1));
  EXPECT_GT(EmbeddingSimilarity(ea1, ea2), EmbeddingSimilarity(ea2, eb1));
  // A box outside the image embeds nothing.
  EXPECT_TRUE(reid->Embed(a1, cv::Rect(300, 300, 10, 10)).empty());
}

}  // namespace
}  // namespace attend
