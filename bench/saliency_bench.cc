// Benchmark: the pre-attentive stage (colour conversions, BIP segmentation, the four built-in
// feature plugins with their defaults and the saliency sum) against OpenCV's static saliency
// detectors (opencv_contrib saliency: spectral residual, Hou and Zhang 2007; fine-grained,
// Montabone and Soto 2010), on the same frames of a synthetic scene, in the same run, on one
// thread.
//
//   saliency_bench [--scene FILE] [--frames N] [--home DIR] [--markdown FILE]
//
// For every method it prints the median milliseconds a frame and how well the map separates
// the scene's objects from the background: the ROC AUC of the map's values for object pixels
// against background pixels, from the renderer's exact object masks (1 = every object pixel
// above every background pixel, 0.5 = chance), averaged over frames. Skin objects count as
// objects. Each method's map is min-max normalised per frame before the AUC; the AUC does not
// depend on it.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/saliency.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "features/builtin.h"
#include "features/feature_set.h"
#include "features/lazy_frame_context.h"
#include "saliency/saliency.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "util/timer.h"

namespace {

using attend::bench::Median;

struct Options {
  std::string scene;
  std::string home = ATTEND_SOURCE_ROOT;
  int frames = 60;
  std::string markdown;
};

// ROC AUC of `map` (CV_32FC1) for the pixels where `positive` is set against the others, by
// ranking through a 4096-bin histogram of the [0, 1]-normalised values (ties count half).
double RocAuc(const cv::Mat& map, const cv::Mat& positive) {
  cv::Mat unit;
  cv::normalize(map, unit, 0.0, 1.0, cv::NORM_MINMAX);
  constexpr int kBins = 4096;
  std::vector<double> pos(kBins, 0.0), neg(kBins, 0.0);
  for (int y = 0; y < unit.rows; ++y) {
    const float* value = unit.ptr<float>(y);
    const uchar* is_positive = positive.ptr<uchar>(y);
    for (int x = 0; x < unit.cols; ++x) {
      const int bin = std::min(kBins - 1, static_cast<int>(value[x] * kBins));
      (is_positive[x] ? pos : neg)[bin] += 1.0;
    }
  }
  double total_pos = 0, total_neg = 0;
  for (int i = 0; i < kBins; ++i) total_pos += pos[i], total_neg += neg[i];
  if (total_pos == 0 || total_neg == 0) return 0.5;
  double below = 0.0, area = 0.0;
  for (int i = 0; i < kBins; ++i) {
    area += pos[i] * (below + 0.5 * neg[i]);
    below += neg[i];
  }
  return area / (total_pos * total_neg);
}

struct Method {
  explicit Method(std::string method_name) : name(std::move(method_name)) {}
  std::string name;
  std::vector<double> ms;
  std::vector<double> auc;
};

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App app{"the pre-attentive stage against OpenCV's static saliency (docs/PERFORMANCE.md)",
               "saliency_bench"};
  app.add_option("--scene", options.scene, "scene file (default: sequences/lab.yaml of --home)");
  app.add_option("--frames", options.frames, "frames to render and time")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  app.add_option("--home", options.home, "attend source tree")->capture_default_str();
  app.add_option("--markdown", options.markdown, "also write the report to FILE");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  if (options.scene.empty()) options.scene = options.home + "/sequences/lab.yaml";
  cv::setNumThreads(1);

  const attend::SceneRenderer renderer(attend::LoadScene(options.scene));
  const attend::FeatureRegistry registry = attend::BuiltinFeatures();
  attend::FeatureSetup setup;
  setup.home = options.home;
  const std::vector<attend::FeatureSpec> specs = attend::ReadFeatureList(
      attend::ParamBlock::Parse("features: [{name: colour_contrast}, {name: intensity_contrast}, "
                                "{name: skin}, {name: disparity}]",
                                "saliency_bench"),
      "features");
  attend::FeatureSet features(specs, registry, setup);
  attend::LazyFrameContext context;
  const attend::SaliencyOptions saliency_options;

  cv::Ptr<cv::saliency::StaticSaliencySpectralResidual> residual =
      cv::saliency::StaticSaliencySpectralResidual::create();
  cv::Ptr<cv::saliency::StaticSaliencyFineGrained> fine =
      cv::saliency::StaticSaliencyFineGrained::create();

  Method ours{"attend: BIP + colour, intensity, skin, disparity + saliency"};
  Method ours_segment{"  of which conversions + BIP segmentation"};
  std::vector<Method> per_feature;
  for (const auto& result : features.results())
    per_feature.emplace_back("  of which " + result.name);
  Method ours_sum{"  of which normalisation and sum"};
  Method spectral{"OpenCV StaticSaliencySpectralResidual"};
  Method fine_grained{"OpenCV StaticSaliencyFineGrained"};

  std::vector<cv::Mat> normalised(features.results().size());
  std::vector<double> weights(features.results().size(), 1.0);
  cv::Mat saliency, residual_map, fine_map, fine_float;
  cv::Size size;
  for (int index = 0; index < options.frames; ++index) {
    const attend::RenderedFrame frame = renderer.Render(index);
    size = frame.left.size();
    const cv::Mat objects = frame.left_ids > 0;

    attend::Stopwatch total;
    context.Reset(index, frame.left, frame.right);
    attend::Stopwatch stage;
    context.Regions();
    ours_segment.ms.push_back(stage.ElapsedMs());
    features.Compute(context);
    stage.Restart();
    for (size_t i = 0; i < normalised.size(); ++i) {
      attend::NormaliseMap(features.results()[i].map, saliency_options, &normalised[i]);
    }
    attend::CombineMaps(normalised, weights, context.size(), &saliency);
    ours_sum.ms.push_back(stage.ElapsedMs());
    ours.ms.push_back(total.ElapsedMs());
    for (size_t i = 0; i < per_feature.size(); ++i) {
      per_feature[i].ms.push_back(features.results()[i].milliseconds);
      per_feature[i].auc.push_back(RocAuc(features.results()[i].map, objects));
    }
    ours.auc.push_back(RocAuc(saliency, objects));

    stage.Restart();
    residual->computeSaliency(frame.left, residual_map);
    spectral.ms.push_back(stage.ElapsedMs());
    spectral.auc.push_back(RocAuc(residual_map, objects));

    stage.Restart();
    fine->computeSaliency(frame.left, fine_map);
    fine_grained.ms.push_back(stage.ElapsedMs());
    fine_map.convertTo(fine_float, CV_32F);
    fine_grained.auc.push_back(RocAuc(fine_float, objects));
  }

  std::ostringstream report;
  report << std::fixed;
  report << "Scene " << options.scene << ", frames 0.." << options.frames - 1 << ", " << size.width
         << "x" << size.height << ", one thread.\n\n";
  report << "| method | ms a frame (median) | object/background ROC AUC (mean) |\n";
  report << "|---|---:|---:|\n";
  std::vector<Method*> rows = {&ours, &ours_segment};
  for (Method& method : per_feature) rows.push_back(&method);
  rows.push_back(&ours_sum);
  rows.push_back(&spectral);
  rows.push_back(&fine_grained);
  for (const Method* method : rows) {
    double auc = 0.0;
    for (const double value : method->auc) auc += value;
    report << "| " << method->name << " | " << std::setprecision(2) << Median(method->ms) << " | "
           << (method->auc.empty() ? std::string("")
                                   : (std::ostringstream() << std::fixed << std::setprecision(3)
                                                           << auc / method->auc.size())
                                         .str())
           << " |\n";
  }
  report << "\nSpeed ratios (median ms of the OpenCV method / attend's whole stage): spectral "
            "residual "
         << std::setprecision(2) << Median(spectral.ms) / Median(ours.ms) << "x, fine-grained "
         << Median(fine_grained.ms) / Median(ours.ms) << "x.\n";
  std::cout << report.str();
  if (!options.markdown.empty()) std::ofstream(options.markdown) << report.str();
  return 0;
}
