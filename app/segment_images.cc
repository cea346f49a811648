#include "app/segment_images.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "io/image_file.h"
#include "util/error.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// Shift variance as in the thesis (3.3.2.1): a window of at most 128 pixels, shifts 0..10.
constexpr int kShiftVarianceWindow = 128;
constexpr int kShiftVarianceMaxShift = 10;

// The labels as a 16-bit PNG: region indices 0..R-1 must fit in 16 bits.
cv::Mat SixteenBitLabels(const std::string& image_path, const Segmentation& segmentation) {
  const size_t regions = segmentation.regions.size();
  if (regions > 65536) {
    throw InputError(image_path + ": " + std::to_string(regions) +
                     " regions do not fit a 16-bit label image (labels 0..65535); raise "
                     "segmentation.t_max to merge more");
  }
  cv::Mat labels16;
  segmentation.labels.convertTo(labels16, CV_16UC1);
  return labels16;
}

}  // namespace

namespace {

// The quality measures of one segmentation (F, Q and the shift variance, or why the image is
// too small for it) into `image` and its report entry.
void AddMetrics(const cv::Mat& bgr, const Segmentation& segmentation,
                const SegmentFunction& segment_window, SegmentedImage* image,
                nlohmann::json* entry) {
  image->quality = EvaluateSegmentation(bgr, segmentation.labels);
  (*entry)["f"] = image->quality->f;
  (*entry)["q"] = image->quality->q;
  const int window =
      std::min(kShiftVarianceWindow, std::min(bgr.cols, bgr.rows) - kShiftVarianceMaxShift);
  if (window > kShiftVarianceMaxShift) {
    image->shift_variance = ShiftVariance(bgr, segment_window, window, kShiftVarianceMaxShift);
    (*entry)["shift_variance"] = *image->shift_variance;
    return;
  }
  const int needed = 2 * kShiftVarianceMaxShift + 1;
  (*entry)["shift_variance"] = nullptr;
  (*entry)["shift_variance_note"] =
      "the image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
      "; shift variance needs at least " + std::to_string(needed) + "x" + std::to_string(needed) +
      " pixels (a window wider than the " + std::to_string(kShiftVarianceMaxShift) +
      "-pixel shift, plus the shift)";
}

}  // namespace

void SegmentImages(const SegmentRequest& request,
                   const std::function<void(const SegmentedImage&)>& on_image) {
  ATTEND_CHECK(request.stems.size() == request.images.size()) << "one stem per image";
  const fs::path out(request.out);
  std::error_code error;
  fs::create_directories(out, error);
  if (error || !fs::is_directory(out)) {
    throw OutputError(request.out + ": cannot create the output folder" +
                      (error ? " (" + error.message() + ")" : std::string()));
  }

  // One pool for the command's pyramids (pyramid/bip.h).
  BipPool pool;
  Segmenter segmenter(request.options, &pool);
  // Windows for the shift variance have their own size; a second segmenter keeps the first
  // one's buffers sized for whole images.
  Segmenter window_segmenter(request.options, &pool);
  Segmentation window_segmentation;
  const SegmentFunction segment_window = [&](const cv::Mat& bgr, cv::Mat* labels) {
    window_segmenter.Segment(bgr, &window_segmentation);
    *labels = window_segmentation.labels;
  };

  nlohmann::json entries = nlohmann::json::array();
  Segmentation segmentation;
  for (size_t i = 0; i < request.images.size(); ++i) {
    const std::string& path = request.images[i];
    // IMREAD_COLOR gives 8-bit BGR whatever the file holds: grey is replicated to three
    // channels and 16-bit samples are scaled to 8 bits.
    const cv::Mat bgr = ReadNamedImageFile(path, cv::IMREAD_COLOR);
    segmenter.Segment(bgr, &segmentation);

    const std::string stem = (out / request.stems[i]).string();
    WriteImageFile(stem + ".labels.png", SixteenBitLabels(path, segmentation));
    WriteImageFile(stem + ".regions.png", FalseColour(segmentation.labels));
    WriteImageFile(stem + ".mean.png", MeanColourImage(segmentation.labels, segmentation.regions));

    SegmentedImage image{path,
                         bgr.size(),
                         segmentation.regions.size(),
                         segmentation.pyramid_levels,
                         segmentation.milliseconds,
                         std::nullopt,
                         std::nullopt};
    nlohmann::json entry = {{"image", path},
                            {"width", bgr.cols},
                            {"height", bgr.rows},
                            {"regions", segmentation.regions.size()},
                            {"pyramid_levels", segmentation.pyramid_levels},
                            {"milliseconds", segmentation.milliseconds}};
    if (request.metrics) AddMetrics(bgr, segmentation, segment_window, &image, &entry);
    entries.push_back(entry);
    if (on_image) on_image(image);
  }

  const nlohmann::json report = {{"images", entries},
                                 {"options",
                                  {{"t_max", request.options.t_max},
                                   {"min_region_area", request.options.min_region_area},
                                   {"merge_spread", request.options.merge_spread},
                                   {"link_across_kinds", request.options.bip.link_across_kinds}}}};
  const fs::path report_path = out / "segment.json";
  std::ofstream file(report_path);
  file << JsonText(report, 2) << "\n";
  file.close();
  if (!file) throw OutputError(report_path.string() + ": cannot write");
}

}  // namespace attend
