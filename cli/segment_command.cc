// attend segment: BIP colour segmentation of still images, with the quality measures of
// thesis 3.3.2 on request (SPEC 3.2, docs/PYRAMID.md).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "cli/cli_options.h"
#include "cli/commands.h"
#include "cli/home.h"
#include "io/image_file.h"
#include "pipeline/options_io.h"
#include "pyramid/metrics.h"
#include "pyramid/segmentation.h"
#include "util/error.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// Shift variance as in the thesis (3.3.2.1): a window of at most 128 pixels, shifts 0..10.
constexpr int kShiftVarianceWindow = 128;
constexpr int kShiftVarianceMaxShift = 10;

struct SegmentArguments {
  std::vector<std::string> images;
  std::string out;
  std::string config;
  std::vector<std::string> sets;
  bool metrics = false;
  bool quiet = false;
};

cv::Mat ReadImage(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) {
    throw InputError(path + ": no such image file");
  }
  // IMREAD_COLOR gives 8-bit BGR whatever the file holds: grey is replicated to three
  // channels and 16-bit samples are scaled to 8 bits.
  return ReadImageFile(path, cv::IMREAD_COLOR, path);
}

void WriteImage(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) {
    throw OutputError(path.string() + ": cannot write the image");
  }
}

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

std::string Fixed(double value, int digits) {
  std::ostringstream text;
  text << std::fixed << std::setprecision(digits) << value;
  return text.str();
}

int Segment(const SegmentArguments& args) {
  const std::string config_path = args.config.empty() ? DefaultConfigPath() : args.config;
  const SegmentationOptions options = LoadOptions(config_path, args.sets).segmentation;
  const std::vector<std::string> stems = OutputStems(args.images, "outputs STEM.*.png");

  const fs::path out(args.out);
  std::error_code error;
  fs::create_directories(out, error);
  if (error || !fs::is_directory(out)) {
    throw OutputError(args.out + ": cannot create the output folder" +
                      (error ? " (" + error.message() + ")" : std::string()));
  }

  Segmenter segmenter(options);
  // Windows for the shift variance have their own size; a second segmenter keeps the first
  // one's buffers sized for whole images.
  Segmenter window_segmenter(options);
  Segmentation window_segmentation;
  const SegmentFunction segment_window = [&](const cv::Mat& bgr, cv::Mat* labels) {
    window_segmenter.Segment(bgr, &window_segmentation);
    *labels = window_segmentation.labels;
  };

  nlohmann::json entries = nlohmann::json::array();
  Segmentation segmentation;
  for (size_t i = 0; i < args.images.size(); ++i) {
    const std::string& path = args.images[i];
    const cv::Mat bgr = ReadImage(path);
    segmenter.Segment(bgr, &segmentation);

    WriteImage(out / (stems[i] + ".labels.png"), SixteenBitLabels(path, segmentation));
    WriteImage(out / (stems[i] + ".regions.png"), FalseColour(segmentation.labels));
    WriteImage(out / (stems[i] + ".mean.png"),
               MeanColourImage(segmentation.labels, segmentation.regions));

    nlohmann::json entry = {{"image", path},
                            {"width", bgr.cols},
                            {"height", bgr.rows},
                            {"regions", segmentation.regions.size()},
                            {"pyramid_levels", segmentation.pyramid_levels},
                            {"milliseconds", segmentation.milliseconds}};
    std::string line = path + ": " + std::to_string(segmentation.regions.size()) + " regions, " +
                       std::to_string(segmentation.pyramid_levels) + " levels, " +
                       Fixed(segmentation.milliseconds, 1) + " ms";
    if (args.metrics) {
      const SegmentationQuality quality = EvaluateSegmentation(bgr, segmentation.labels);
      entry["f"] = quality.f;
      entry["q"] = quality.q;
      line += ", F " + Fixed(quality.f, 4) + ", Q " + Fixed(quality.q, 4);
      const int window =
          std::min(kShiftVarianceWindow, std::min(bgr.cols, bgr.rows) - kShiftVarianceMaxShift);
      if (window > kShiftVarianceMaxShift) {
        const double sv = ShiftVariance(bgr, segment_window, window, kShiftVarianceMaxShift);
        entry["shift_variance"] = sv;
        line += ", SV " + Fixed(sv, 3);
      } else {
        const int needed = 2 * kShiftVarianceMaxShift + 1;
        entry["shift_variance"] = nullptr;
        entry["shift_variance_note"] =
            "the image is " + std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) +
            "; shift variance needs at least " + std::to_string(needed) + "x" +
            std::to_string(needed) + " pixels (a window wider than the " +
            std::to_string(kShiftVarianceMaxShift) + "-pixel shift, plus the shift)";
        line += ", SV n/a (image too small)";
      }
    }
    entries.push_back(entry);
    if (!args.quiet) std::cout << line << std::endl;
  }

  const nlohmann::json report = {{"images", entries},
                                 {"options",
                                  {{"t_max", options.t_max},
                                   {"min_region_area", options.min_region_area},
                                   {"link_across_kinds", options.bip.link_across_kinds}}}};
  const fs::path report_path = out / "segment.json";
  std::ofstream file(report_path);
  file << JsonText(report, 2) << "\n";
  file.close();
  if (!file) throw OutputError(report_path.string() + ": cannot write");
  return 0;
}

}  // namespace

void AddSegmentCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<SegmentArguments>();
  CLI::App* segment = app.add_subcommand(
      "segment",
      "Segment images with the Bounded Irregular Pyramid (docs/PYRAMID.md). Every image is read "
      "as 8-bit BGR: grey images become three equal channels and 16-bit images are scaled to 8 "
      "bits. For each IMAGE writes OUT/<stem>.labels.png (16-bit region labels), "
      "OUT/<stem>.regions.png (false colour) and OUT/<stem>.mean.png (region mean colours), then "
      "OUT/segment.json. OUT may already hold other files: only these named files are written "
      "(and replaced).");
  segment->add_option("IMAGE", args->images, "Images to segment (their stems must differ)")
      ->required();
  segment->add_option("--out", args->out, "Output folder, created if missing")->required();
  segment->add_option("--config", args->config,
                      "Configuration YAML; its segmentation block is used (default: "
                      "configs/default.yaml of the attend home)");
  AddSetOption(segment, &args->sets,
               "Override a configuration key, the value parsed as YAML: "
               "--set segmentation.t_max=30 (repeatable)");
  segment->add_flag("--metrics", args->metrics,
                    "Also compute F, Q and the shift variance (thesis 3.3.2; smaller is better)");
  segment->add_flag("--quiet", args->quiet, "No line per image; errors only");
  segment->callback([args, action] { *action = [args] { return Segment(*args); }; });
}

}  // namespace attend
