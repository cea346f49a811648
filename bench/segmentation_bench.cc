// Benchmark (SPEC 5): BIP colour segmentation (pyramid/segmentation.h) against Felzenszwalb and
// Huttenlocher's graph segmentation (OpenCV ximgproc), on the same images in the same run, on
// one thread. Prints a markdown report; docs/PERFORMANCE.md holds one with its command.
//
//   segmentation_bench [--data DIR] [--repeat N] [--markdown FILE]
//
// What is timed, as the median of N repetitions after one warm-up (the methods take turns, one
// call each per round, so that load from other processes falls on all of them alike):
//   BIP: BgrToCylinder plus Segmenter::SegmentCylinder (pyramid, root labels, region statistics
//        and region adjacency graph, small-region merging, and for the spread-merge variant the
//        merge by spread of configs/segment.yaml); the "core" column is
//        Segmentation::milliseconds of the same calls, the Segmenter's own timing.
//   Felzenszwalb: GraphSegmentation::processImage on the same 8-bit BGR image.
// Regions are counted as distinct labels and as 8-connected regions; Q and F are computed on
// the 8-connected regions, as the thesis does for methods whose regions may be unconnected.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/segmentation.hpp>
#include <yaml-cpp/yaml.h>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.h"
#include "colour/colour.h"
#include "pyramid/metrics.h"
#include "pyramid/segmentation.h"
#include "util/timer.h"

namespace {

namespace fs = std::filesystem;

constexpr float kTmaxValues[] = {20.f, 30.f, 40.f, 50.f};

// The settings of `attend segment`, from configs/segment.yaml: the spread-merge variant runs
// with its merge_spread, and is compared with Felzenszwalb at its t_max.
struct SegmentDefaults {
  float t_max = 0.f;
  float merge_spread = 0.f;
};

const SegmentDefaults& SegmentYaml() {
  static const SegmentDefaults defaults = [] {
    const std::string path = std::string(ATTEND_SOURCE_ROOT) + "/configs/segment.yaml";
    const YAML::Node block = YAML::LoadFile(path)["segmentation"];
    SegmentDefaults d;
    d.t_max = block["t_max"].as<float>();
    d.merge_spread = block["merge_spread"].as<float>();
    return d;
  }();
  return defaults;
}
constexpr float kFelzenszwalbK[] = {25.f, 50.f, 100.f, 300.f, 500.f, 1000.f, 2000.f, 4000.f};
constexpr double kFelzenszwalbSigma = 0.5;
constexpr int kFelzenszwalbMinSize = 20;

using Options = attend::bench::BenchOptions;
using attend::bench::CpuModel;
using attend::bench::Fixed;
using attend::bench::Median;
using attend::bench::UtcNow;

struct SourceImage {
  std::string name;
  cv::Mat bgr;  // 8-bit BGR at its own size
};

struct BenchSize {
  std::string name;
  cv::Size size;
};

// kBip and kBipLinked are the thesis's regions (merge_spread 0), with the faithful rules and
// with bip.link_across_kinds; kBipSpread is the default, the faithful rules followed by the
// merge by spread (SegmentationOptions::merge_spread).
enum class Method { kBip, kBipLinked, kBipSpread, kFelzenszwalb };
constexpr Method kBipMethods[] = {Method::kBip, Method::kBipLinked, Method::kBipSpread};

const char* MethodName(Method method) {
  switch (method) {
    case Method::kBip:
      return "BIP";
    case Method::kBipLinked:
      return "BIP linked";
    case Method::kBipSpread:
      return "BIP spread merge";
    case Method::kFelzenszwalb:
      return "Felzenszwalb";
  }
  return "?";
}

struct Result {
  std::string image;
  std::string size;
  Method method = Method::kBip;
  float parameter = 0.f;  // t_max for the BIP, k for Felzenszwalb
  double median_ms = 0.0;
  double core_ms = -1.0;                // BIP: median Segmentation::milliseconds; -1 otherwise
  int min_region_area = 0;              // BIP: SegmentationOptions::min_region_area
  int levels = 0;                       // BIP: pyramid height; 0 otherwise
  int labels = 0;                       // distinct labels
  int connected = 0;                    // 8-connected regions
  attend::SegmentationQuality quality;  // over the 8-connected regions
};

// Four rectangles of distinct colours tiling the image: four regions by construction.
cv::Mat MakeRectangles() {
  cv::Mat image(480, 640, CV_8UC3);
  image(cv::Rect(0, 0, 320, 240)).setTo(cv::Scalar(40, 40, 200));
  image(cv::Rect(320, 0, 320, 240)).setTo(cv::Scalar(40, 180, 40));
  image(cv::Rect(0, 240, 320, 240)).setTo(cv::Scalar(200, 60, 30));
  image(cv::Rect(320, 240, 320, 240)).setTo(cv::Scalar(30, 200, 220));
  return image;
}

// A smooth two-way colour gradient with three flat shapes on it.
cv::Mat MakeGradient() {
  cv::Mat image(480, 640, CV_8UC3);
  for (int row = 0; row < image.rows; ++row) {
    cv::Vec3b* pixel = image.ptr<cv::Vec3b>(row);
    for (int col = 0; col < image.cols; ++col) {
      pixel[col] =
          cv::Vec3b(static_cast<uchar>(40 + 180 * col / image.cols),
                    static_cast<uchar>(40 + 180 * row / image.rows),
                    static_cast<uchar>(200 - 120 * (col + row) / (image.cols + image.rows)));
    }
  }
  cv::circle(image, cv::Point(170, 150), 90, cv::Scalar(20, 20, 230), cv::FILLED);
  cv::rectangle(image, cv::Rect(380, 80, 200, 130), cv::Scalar(230, 230, 230), cv::FILLED);
  const std::vector<cv::Point> triangle = {{300, 440}, {460, 260}, {600, 440}};
  cv::fillConvexPoly(image, triangle, cv::Scalar(30, 120, 20));
  return image;
}

// A 4 x 3 grid of patches, each a base colour with a stripe or checker texture, plus Gaussian
// noise over everything (fixed seed).
cv::Mat MakeTextured() {
  cv::Mat image(480, 640, CV_8UC3);
  cv::RNG rng(20240611);
  const int patch_w = 160, patch_h = 160;
  for (int py = 0; py < 3; ++py) {
    for (int px = 0; px < 4; ++px) {
      const cv::Vec3b base(static_cast<uchar>(rng.uniform(30, 226)),
                           static_cast<uchar>(rng.uniform(30, 226)),
                           static_cast<uchar>(rng.uniform(30, 226)));
      const int kind = (px + py) % 3;  // 0 stripes, 1 checker, 2 flat
      const int period = 6 + 4 * ((px + 2 * py) % 3);
      for (int row = py * patch_h; row < (py + 1) * patch_h; ++row) {
        cv::Vec3b* pixel = image.ptr<cv::Vec3b>(row);
        for (int col = px * patch_w; col < (px + 1) * patch_w; ++col) {
          bool dark = false;
          if (kind == 0) dark = (col / period) % 2 == 1;
          if (kind == 1) dark = ((col / period) + (row / period)) % 2 == 1;
          cv::Vec3b value = base;
          if (dark) value = cv::Vec3b(base[0] * 3 / 4, base[1] * 3 / 4, base[2] * 3 / 4);
          pixel[col] = value;
        }
      }
    }
  }
  cv::Mat noise(image.size(), CV_16SC3);
  rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(12));
  cv::Mat noisy;
  image.convertTo(noisy, CV_16SC3);
  noisy += noise;
  noisy.convertTo(image, CV_8UC3);  // saturates to [0, 255]
  return image;
}

void AddIfPresent(const fs::path& path, const std::string& name, std::vector<SourceImage>* out) {
  if (!fs::exists(path)) {
    std::cerr << "segmentation_bench: skipping " << name << ": " << path.string() << " not found\n";
    return;
  }
  cv::Mat bgr = cv::imread(path.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) {
    std::cerr << "segmentation_bench: skipping " << name << ": cannot read " << path.string()
              << "\n";
    return;
  }
  out->push_back({name, bgr});
}

std::vector<SourceImage> LoadImages(const std::string& data_dir) {
  std::vector<SourceImage> images;
  if (data_dir.empty()) {
    std::cerr << "segmentation_bench: no --data given: Middlebury and OTB images skipped\n";
  } else {
    const fs::path root(data_dir);
    const std::pair<const char*, const char*> middlebury[] = {
        {"tsukuba", "im3.png"}, {"venus", "im2.png"}, {"teddy", "im2.png"}, {"cones", "im2.png"}};
    for (const auto& [pair, file] : middlebury) {
      AddIfPresent(root / "middlebury" / pair / file, pair, &images);
    }
    const fs::path otb = root / "otb";
    if (!fs::is_directory(otb)) {
      std::cerr << "segmentation_bench: skipping OTB: " << otb.string() << " not found\n";
    } else {
      std::vector<fs::path> sequences;
      for (const auto& entry : fs::directory_iterator(otb)) {
        if (entry.is_directory()) sequences.push_back(entry.path());
      }
      std::sort(sequences.begin(), sequences.end());
      for (const fs::path& sequence : sequences) {
        AddIfPresent(sequence / "img" / "0001.jpg", "otb-" + sequence.filename().string(), &images);
      }
    }
  }
  images.push_back({"synth-rectangles", MakeRectangles()});
  images.push_back({"synth-gradient", MakeGradient()});
  images.push_back({"synth-texture", MakeTextured()});
  return images;
}

cv::Mat Resized(const cv::Mat& bgr, cv::Size size) {
  if (bgr.size() == size) return bgr.clone();
  const bool shrinking = size.width <= bgr.cols && size.height <= bgr.rows;
  cv::Mat out;
  cv::resize(bgr, out, size, 0, 0, shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);
  return out;
}

int CountDistinctLabels(const cv::Mat& labels) {
  std::vector<bool> seen;
  int count = 0;
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    for (int col = 0; col < labels.cols; ++col) {
      const int l = label[col];
      if (l < 0) continue;
      if (static_cast<size_t>(l) >= seen.size()) seen.resize(l + 1, false);
      if (!seen[l]) {
        seen[l] = true;
        ++count;
      }
    }
  }
  return count;
}

// Splits every label of `labels` (CV_32SC1) into its 8-connected components, numbered from 0
// in raster order of first pixel; pixels < 0 stay -1. Returns the number of components.
int SplitConnected(const cv::Mat& labels, cv::Mat* out) {
  *out = cv::Mat(labels.size(), CV_32SC1, cv::Scalar(-1));
  std::vector<cv::Point> stack;
  int next = 0;
  for (int row = 0; row < labels.rows; ++row) {
    for (int col = 0; col < labels.cols; ++col) {
      const int label = labels.at<int32_t>(row, col);
      if (label < 0 || out->at<int32_t>(row, col) >= 0) continue;
      const int component = next++;
      out->at<int32_t>(row, col) = component;
      stack.assign(1, cv::Point(col, row));
      while (!stack.empty()) {
        const cv::Point p = stack.back();
        stack.pop_back();
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int x = p.x + dx, y = p.y + dy;
            if (x < 0 || y < 0 || x >= labels.cols || y >= labels.rows) continue;
            if (labels.at<int32_t>(y, x) != label || out->at<int32_t>(y, x) >= 0) continue;
            out->at<int32_t>(y, x) = component;
            stack.emplace_back(x, y);
          }
        }
      }
    }
  }
  return next;
}

void Measure(const cv::Mat& bgr, const cv::Mat& labels, Result* result) {
  result->labels = CountDistinctLabels(labels);
  cv::Mat connected;
  result->connected = SplitConnected(labels, &connected);
  result->quality = attend::EvaluateSegmentation(bgr, connected);
}

// One method with one setting on one image. Run() is the timed call; Finish() fills the
// method's fields of the result from the last Run().
class Contender {
 public:
  virtual ~Contender() = default;
  virtual void Run() = 0;
  virtual void Finish(Result* result) = 0;
};

class BipContender : public Contender {
 public:
  BipContender(const cv::Mat& bgr, Method method, float t_max)
      : bgr_(bgr), method_(method), t_max_(t_max), segmenter_(MakeOptions(method, t_max)) {}

  void Run() override {
    attend::BgrToCylinder(bgr_, &cylinder_);
    segmenter_.SegmentCylinder(cylinder_, &segmentation_);
    core_ms_.push_back(segmentation_.milliseconds);
  }

  void Finish(Result* result) override {
    result->method = method_;
    result->parameter = t_max_;
    // The first call was the warm-up.
    result->core_ms = Median(std::vector<double>(core_ms_.begin() + 1, core_ms_.end()));
    result->min_region_area = segmenter_.options().min_region_area;
    result->levels = segmentation_.pyramid_levels;
    Measure(bgr_, segmentation_.labels, result);
  }

 private:
  static attend::SegmentationOptions MakeOptions(Method method, float t_max) {
    attend::SegmentationOptions options;
    options.t_max = t_max;
    options.bip.link_across_kinds = method == Method::kBipLinked;
    options.merge_spread = method == Method::kBipSpread ? SegmentYaml().merge_spread : 0.f;
    return options;
  }

  const cv::Mat& bgr_;
  Method method_;
  float t_max_;
  attend::Segmenter segmenter_;
  cv::Mat cylinder_;
  attend::Segmentation segmentation_;
  std::vector<double> core_ms_;
};

class FelzenszwalbContender : public Contender {
 public:
  FelzenszwalbContender(const cv::Mat& bgr, float k)
      : bgr_(bgr),
        k_(k),
        segmenter_(cv::ximgproc::segmentation::createGraphSegmentation(kFelzenszwalbSigma, k,
                                                                       kFelzenszwalbMinSize)) {}

  void Run() override { segmenter_->processImage(bgr_, labels_); }

  void Finish(Result* result) override {
    result->method = Method::kFelzenszwalb;
    result->parameter = k_;
    Measure(bgr_, labels_, result);
  }

 private:
  const cv::Mat& bgr_;
  float k_;
  cv::Ptr<cv::ximgproc::segmentation::GraphSegmentation> segmenter_;
  cv::Mat labels_;
};

// Runs every method and setting on `bgr`: one warm-up call each, then `repeat` rounds in which
// each is called once, so that a change in the machine's load affects all of them alike.
std::vector<Result> RunAll(const cv::Mat& bgr, int repeat) {
  std::vector<std::unique_ptr<Contender>> contenders;
  for (const Method method : kBipMethods) {
    for (const float t_max : kTmaxValues) {
      contenders.push_back(std::make_unique<BipContender>(bgr, method, t_max));
    }
  }
  for (const float k : kFelzenszwalbK) {
    contenders.push_back(std::make_unique<FelzenszwalbContender>(bgr, k));
  }
  for (auto& contender : contenders) contender->Run();
  std::vector<std::vector<double>> times(contenders.size());
  for (int round = 0; round < repeat; ++round) {
    for (size_t i = 0; i < contenders.size(); ++i) {
      const attend::Stopwatch watch;
      contenders[i]->Run();
      times[i].push_back(watch.ElapsedMs());
    }
  }
  std::vector<Result> results(contenders.size());
  for (size_t i = 0; i < contenders.size(); ++i) {
    results[i].median_ms = Median(times[i]);
    contenders[i]->Finish(&results[i]);
  }
  return results;
}

// `digits` significant digits, for Q and F whose magnitudes vary by orders of magnitude.
std::string Significant(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.*g", digits, value);
  return buffer;
}

std::string Parameters(const Result& r) {
  if (r.method == Method::kFelzenszwalb) {
    return "sigma " + Fixed(kFelzenszwalbSigma, 1) + ", k " + Fixed(r.parameter, 0) +
           ", min_size " + std::to_string(kFelzenszwalbMinSize);
  }
  return "t_max " + Fixed(r.parameter, 0) + ", min area " + std::to_string(r.min_region_area);
}

struct Stats {
  double min = 0.0, avg = 0.0, max = 0.0;
};

Stats Summarise(const std::vector<double>& values) {
  Stats s;
  if (values.empty()) return s;
  s.min = *std::min_element(values.begin(), values.end());
  s.max = *std::max_element(values.begin(), values.end());
  double sum = 0.0;
  for (double v : values) sum += v;
  s.avg = sum / static_cast<double>(values.size());
  return s;
}

std::string StatsCell(const Stats& s, int digits) {
  return Fixed(s.min, digits) + " / " + Fixed(s.avg, digits) + " / " + Fixed(s.max, digits);
}

// The Felzenszwalb result on the same image and size whose connected region count is closest
// to `bip`'s (ties: the smaller k).
const Result* ClosestFelzenszwalb(const std::vector<Result>& results, const Result& bip) {
  const Result* best = nullptr;
  for (const Result& r : results) {
    if (r.method != Method::kFelzenszwalb || r.image != bip.image || r.size != bip.size) continue;
    if (best == nullptr ||
        std::abs(r.connected - bip.connected) < std::abs(best->connected - bip.connected)) {
      best = &r;
    }
  }
  return best;
}

void WriteReport(const Options& options, const std::vector<SourceImage>& images,
                 const std::vector<BenchSize>& sizes, const std::vector<Result>& results,
                 std::ostream& out) {
  // The thesis's variants at SegmentationOptions' t_max (the attention loop's), the spread
  // merge at configs/segment.yaml's.
  const auto default_t_max = [](Method method) {
    return method == Method::kBipSpread ? SegmentYaml().t_max : attend::SegmentationOptions{}.t_max;
  };
  out << "Date: " << UtcNow() << "; CPU: " << CpuModel()
      << "; nproc: " << std::thread::hardware_concurrency() << "; OpenCV " << CV_VERSION
      << "; cv::getNumThreads() = " << cv::getNumThreads() << "; repetitions: " << options.repeat
      << " (median, after one warm-up; the methods take turns, one call each per round).\n\n";
  out << "Images:";
  for (size_t i = 0; i < images.size(); ++i) {
    out << (i == 0 ? " " : ", ") << images[i].name << " (" << images[i].bgr.cols << "x"
        << images[i].bgr.rows << ")";
  }
  out << "; each resized to";
  for (const BenchSize& size : sizes) out << " " << size.name;
  out << ".\n\n";
  out << "BIP: the thesis's rules; BIP linked: bip.link_across_kinds; BIP spread merge: the "
         "thesis's rules followed by the merge by spread (merge_spread "
      << Fixed(SegmentYaml().merge_spread, 2)
      << ", configs/segment.yaml, the default of attend segment). "
         "BIP ms: BgrToCylinder + Segmenter::SegmentCylinder (pyramid, labels, region statistics "
         "and adjacency graph, small-region merging, merge by spread); core ms: Segmentation::milliseconds, the "
         "Segmenter's own timing of the same calls. "
         "Felzenszwalb ms: GraphSegmentation::processImage. Q and F (smaller is better) over the "
         "8-connected regions. FH/BIP time uses BIP ms; FH/BIP core uses core ms.\n\n";

  out << "### All runs\n\n";
  out << "| image | size | method | parameters | median ms | core ms | levels | labels | "
         "connected regions | Q | F |\n";
  out << "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Result& r : results) {
    out << "| " << r.image << " | " << r.size << " | " << MethodName(r.method) << " | "
        << Parameters(r) << " | " << Fixed(r.median_ms, 2) << " | "
        << (r.core_ms >= 0.0 ? Fixed(r.core_ms, 2) : "") << " | "
        << (r.levels > 0 ? std::to_string(r.levels) : "") << " | " << r.labels << " | "
        << r.connected << " | " << Significant(r.quality.q, 4) << " | "
        << Significant(r.quality.f, 4) << " |\n";
  }

  out << "\n### Felzenszwalb / BIP at comparable region counts (BIP t_max "
      << Fixed(default_t_max(Method::kBip), 0) << ", spread merge t_max "
      << Fixed(default_t_max(Method::kBipSpread), 0)
      << "; Felzenszwalb k whose connected region count is closest)\n\n";
  out << "| image | size | BIP variant | BIP regions | BIP ms | BIP Q | FH k | FH regions | FH ms "
         "| "
         "FH Q | FH/BIP time | FH/BIP core | BIP Q no worse |\n";
  out << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  struct Pairing {
    double ratio;
    bool q_ok;
    double bip_ms;
    bool photograph;  // a real image, not one of the synthetic ones
    bool connected;   // every label one 8-connected region
  };
  std::map<std::pair<std::string, Method>, std::vector<Pairing>> pairings;
  for (const BenchSize& size : sizes) {
    for (const Method method : kBipMethods) {
      for (const Result& bip : results) {
        if (bip.method != method || bip.size != size.name ||
            bip.parameter != default_t_max(method)) {
          continue;
        }
        const Result* fh = ClosestFelzenszwalb(results, bip);
        if (fh == nullptr) continue;
        const double ratio = fh->median_ms / bip.median_ms;
        const bool q_ok = bip.quality.q <= fh->quality.q;
        pairings[{size.name, method}].push_back({ratio, q_ok, bip.median_ms,
                                                 bip.image.rfind("synth-", 0) != 0,
                                                 bip.labels == bip.connected});
        out << "| " << bip.image << " | " << size.name << " | " << MethodName(method) << " | "
            << bip.connected << " | " << Fixed(bip.median_ms, 2) << " | "
            << Significant(bip.quality.q, 4) << " | " << Fixed(fh->parameter, 0) << " | "
            << fh->connected << " | " << Fixed(fh->median_ms, 2) << " | "
            << Significant(fh->quality.q, 4) << " | " << Fixed(ratio, 1) << "x | "
            << Fixed(fh->median_ms / bip.core_ms, 1) << "x | " << (q_ok ? "yes" : "no") << " |\n";
      }
    }
  }

  out << "\n### SPEC 5 per size (target: Felzenszwalb/BIP >= 10x with BIP Q no worse; "
         "256x256 under 2 ms)\n\n";
  out << "| size | BIP variant | images | FH/BIP min | FH/BIP median | FH/BIP geomean | "
         "images >= 10x | images with Q no worse | BIP ms max | met |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const BenchSize& size : sizes) {
    for (const Method method : kBipMethods) {
      const auto found = pairings.find({size.name, method});
      if (found == pairings.end()) continue;
      const std::vector<Pairing>& list = found->second;
      std::vector<double> ratios;
      double log_sum = 0.0, bip_max = 0.0;
      int fast = 0, q_ok = 0;
      for (const Pairing& p : list) {
        ratios.push_back(p.ratio);
        log_sum += std::log(p.ratio);
        if (p.ratio >= 10.0) ++fast;
        if (p.q_ok) ++q_ok;
        bip_max = std::max(bip_max, p.bip_ms);
      }
      const int n = static_cast<int>(list.size());
      const bool time_ok = size.size != cv::Size(256, 256) || bip_max < 2.0;
      const bool met = fast == n && q_ok == n && time_ok;
      out << "| " << size.name << " | " << MethodName(method) << " | " << n << " | "
          << Fixed(*std::min_element(ratios.begin(), ratios.end()), 1) << "x | "
          << Fixed(Median(ratios), 1) << "x | " << Fixed(std::exp(log_sum / n), 1) << "x | " << fast
          << "/" << n << " | " << q_ok << "/" << n << " | " << Fixed(bip_max, 2) << " | "
          << (met ? "yes" : "no") << " |\n";
    }
  }

  out << "\n### Issue 29 per size, photographs only (target: on every photograph Q no worse "
         "than Felzenszwalb's at the closest region count, Felzenszwalb/BIP >= 10x, no "
         "disconnected region)\n\n";
  out << "| size | BIP variant | photographs | Q no worse | >= 10x | FH/BIP min | "
         "disconnected regions | met |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---|\n";
  for (const BenchSize& size : sizes) {
    for (const Method method : kBipMethods) {
      const auto found = pairings.find({size.name, method});
      if (found == pairings.end()) continue;
      int n = 0, q_ok = 0, fast = 0, split = 0;
      double min_ratio = std::numeric_limits<double>::infinity();
      for (const Pairing& p : found->second) {
        if (!p.photograph) continue;
        ++n;
        q_ok += p.q_ok;
        fast += p.ratio >= 10.0;
        split += !p.connected;
        min_ratio = std::min(min_ratio, p.ratio);
      }
      if (n == 0) continue;
      out << "| " << size.name << " | " << MethodName(method) << " | " << n << " | " << q_ok
          << "/" << n << " | " << fast << "/" << n << " | " << Fixed(min_ratio, 1) << "x | "
          << split << " | " << (q_ok == n && fast == n && split == 0 ? "yes" : "no") << " |\n";
    }
  }

  out << "\n### Table 3.1 style summary (min / avg / max over images; BIP t_max "
      << Fixed(default_t_max(Method::kBip), 0) << ", spread merge t_max "
      << Fixed(default_t_max(Method::kBipSpread), 0) << ", Felzenszwalb at the closest k)\n\n";
  out << "| size | method | time ms | hierarchy height | connected regions |\n";
  out << "|---|---|---|---|---|\n";
  for (const BenchSize& size : sizes) {
    for (const Method method : kBipMethods) {
      std::vector<double> times, heights, regions, fh_times, fh_regions;
      for (const Result& r : results) {
        if (r.method != method || r.size != size.name || r.parameter != default_t_max(method)) {
          continue;
        }
        times.push_back(r.median_ms);
        heights.push_back(r.levels);
        regions.push_back(r.connected);
        if (const Result* fh = ClosestFelzenszwalb(results, r); fh != nullptr) {
          fh_times.push_back(fh->median_ms);
          fh_regions.push_back(fh->connected);
        }
      }
      if (times.empty()) continue;
      out << "| " << size.name << " | " << MethodName(method) << " | "
          << StatsCell(Summarise(times), 2) << " | " << StatsCell(Summarise(heights), 1) << " | "
          << StatsCell(Summarise(regions), 1) << " |\n";
      out << "| " << size.name << " | Felzenszwalb (closest to " << MethodName(method) << ") | "
          << StatsCell(Summarise(fh_times), 2) << " | - | " << StatsCell(Summarise(fh_regions), 1)
          << " |\n";
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  options.data_dir = "";
  options.home = "";
  options.repeat = 15;
  const int status = attend::bench::ParseBenchOptions(
      "segmentation_bench",
      "BIP segmentation against Felzenszwalb graph segmentation (docs/PERFORMANCE.md)",
      "reference data folder (middlebury/, otb/); without it, only the synthetic images", argc,
      argv, &options);
  if (status >= 0) return status;
  cv::setNumThreads(1);

  const std::vector<SourceImage> images = LoadImages(options.data_dir);
  const std::vector<BenchSize> sizes = {{"256x256", cv::Size(256, 256)},
                                        {"640x480", cv::Size(640, 480)}};
  std::vector<Result> results;
  for (const SourceImage& image : images) {
    for (const BenchSize& size : sizes) {
      std::cerr << "segmentation_bench: " << image.name << " at " << size.name << "\n";
      const cv::Mat bgr = Resized(image.bgr, size.size);
      std::vector<Result> batch = RunAll(bgr, options.repeat);
      for (Result& r : batch) {
        r.image = image.name;
        r.size = size.name;
        results.push_back(r);
      }
    }
  }

  std::ostringstream report;
  WriteReport(options, images, sizes, results, report);
  std::cout << report.str();
  if (!options.markdown_path.empty()) {
    std::ofstream file(options.markdown_path);
    file << report.str();
    if (!file) {
      std::cerr << "segmentation_bench: cannot write " << options.markdown_path << "\n";
      return 1;
    }
  }
  return 0;
}
