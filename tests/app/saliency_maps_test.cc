#include "app/saliency_maps.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/pfm.h"
#include "pipeline/options_io.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

TEST(WriteSaliencyMaps, TellsWhatIsLeftOutAndWhatCannotBeReadAndMapsTheRest) {
  testing::TempDir dir;
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(120, 120, 120));
  cv::rectangle(image, cv::Rect(40, 10, 12, 12), cv::Scalar(30, 30, 230), cv::FILLED);
  ASSERT_TRUE(cv::imwrite(dir.File("a.png"), image));
  dir.Write("broken.png", "not a png");
  SaliencyMapsRequest request;
  request.images = {dir.File("broken.png"), dir.File("a.png")};
  request.out = dir.File("out");
  request.home = testing::ProjectRoot();
  request.options = ReadOptions(
      ParamBlock::Parse("features: [{name: colour_contrast}, {name: disparity}]", "c.yaml"));
  std::vector<std::string> left_out, unreadable;
  SaliencyMapsObserver observer;
  observer.on_left_out = [&](const std::string& name) { left_out.push_back(name); };
  observer.on_unreadable = [&](const InputError& e) { unreadable.push_back(e.what()); };
  const SaliencyMapsResult result = WriteSaliencyMaps(request, observer);

  EXPECT_EQ(left_out, std::vector<std::string>{"disparity"});
  ASSERT_EQ(unreadable.size(), 1u);
  EXPECT_EQ(unreadable[0].rfind(dir.File("broken.png"), 0), 0u) << unreadable[0];
  EXPECT_EQ(result.written, 1);
  EXPECT_EQ(result.failed, std::vector<std::string>{dir.File("broken.png")});
  // The map is at the image's size, and its most salient pixel is on the red square.
  const cv::Mat map = ReadPfm(dir.File("out/a.pfm"));
  ASSERT_EQ(map.size(), image.size());
  cv::Point peak;
  cv::minMaxLoc(map, nullptr, nullptr, nullptr, &peak);
  EXPECT_TRUE(cv::Rect(40, 10, 12, 12).contains(peak)) << peak;
  EXPECT_TRUE(fs::exists(dir.File("out/a.png")));
  EXPECT_TRUE(fs::exists(dir.File("out/saliency.json")));
  EXPECT_FALSE(fs::exists(dir.File("out/scanpath.json")));
}

}  // namespace
}  // namespace attend
