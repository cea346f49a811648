// Benchmark (SPEC 5): the disparity estimator (stereo/disparity.h) against OpenCV's StereoBM
// and StereoSGBM, on the same pairs, at the same size and disparity range, in the same run, on
// one thread. Prints a markdown report; docs/DISPARITY.md holds one with its command.
//
//   disparity_bench [--data DIR] [--home DIR] [--repeat N] [--markdown FILE]
//
// Pairs: the four Middlebury pairs under DIR/middlebury (skipped with a message when absent),
// at full size, and frames rendered from sequences/lab.yaml and sequences/occlusions.yaml with
// their exact ground truth, plus the lab scene rendered at 640x480 for SPEC 5's size.
//
// What is timed, as the median of N rounds after one warm-up round (in each round every
// method runs once, in turn, so that load from other processes falls on all of them alike):
//   ours:  DisparityEstimator::Compute on the 8-bit BGR pair (its grey conversion included);
//   BM:    grey conversion of both views + StereoBM::compute;
//   SGBM:  grey conversion of both views + StereoSGBM::compute (MODE_SGBM); and once more on
//          the BGR views directly (cn = 3), SGBM's best case.
// OpenCV's fixed-point output (1/16 px) is converted to pixels and its invalid pixels are
// evaluated twice: counted as bad, and filled from the nearest valid pixel on their row (the
// smaller disparity of the two sides), both outside the timing.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.h"
#include "bench/bench_scenes.h"
#include "bench/sgbm_peer.h"
#include "eval/disparity_scores.h"
#include "stereo/disparity.h"
#include "stereo/disparity_internal.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "util/timer.h"

namespace {

namespace fs = std::filesystem;

// OpenCV's parameters. StereoBM as in OpenCV's samples/cpp/stereo_match.cpp; StereoSGBM the
// same with a 5x5 block and the penalties the OpenCV documentation recommends.
constexpr int kBmBlockSize = 9;
constexpr int kBmPreFilterCap = 31;
constexpr int kBmTextureThreshold = 10;
constexpr int kBmUniquenessRatio = 15;
using attend::bench::kDisp12MaxDiff;
using attend::bench::kSgbmBlockSize;
using attend::bench::kSgbmPreFilterCap;
using attend::bench::kSgbmUniquenessRatio;
using attend::bench::kSpeckleRange;
using attend::bench::kSpeckleWindowSize;
using attend::bench::OpenCvDisparities;

// The synthetic scenes' frames and range: the nearest object of lab.yaml is at 22.5 px, of
// occlusions.yaml at 18 px; at 640x480 the lab scene's disparities double.
constexpr int kLabFrames[] = {0, 40, 80};
constexpr int kOcclusionFrames[] = {0, 30, 65};
constexpr int kSynthMaxDisparity = 32;
constexpr int kLargeFrame = 40;
constexpr int kLargeMaxDisparity = 64;

using Options = attend::bench::BenchOptions;
using attend::bench::CpuModel;
using attend::bench::Fixed;
using attend::bench::Median;
using attend::bench::UtcNow;

struct Pair {
  std::string name;
  std::string source;
  cv::Mat left;          // CV_8UC3, BGR
  cv::Mat right;         // CV_8UC3, BGR
  cv::Mat ground_truth;  // CV_32FC1, pixels; 0 or not finite where unknown
  int max_disparity = 0;
};


// Adds a Middlebury pair when its three files are readable; says why it is skipped otherwise.
void AddMiddlebury(const fs::path& root, const std::string& set, const std::string& name,
                   const std::string& left_file, const std::string& right_file,
                   const std::string& gt_file, double scale, int max_disparity,
                   std::vector<Pair>* pairs) {
  const fs::path folder = root / set / name;
  Pair pair;
  pair.name = name;
  pair.source = "Middlebury " + std::string(set == "middlebury" ? "" : "2005 ") + name + " " +
                left_file + ", " + right_file + "; " + gt_file + " / " +
                std::to_string(static_cast<int>(scale));
  pair.max_disparity = max_disparity;
  pair.left = cv::imread((folder / left_file).string(), cv::IMREAD_COLOR);
  pair.right = cv::imread((folder / right_file).string(), cv::IMREAD_COLOR);
  const cv::Mat gt = cv::imread((folder / gt_file).string(), cv::IMREAD_UNCHANGED);
  if (pair.left.empty() || pair.right.empty() || gt.empty()) {
    std::cerr << "disparity_bench: skipping " << name << ": cannot read " << folder.string() << "/{"
              << left_file << ", " << right_file << ", " << gt_file << "}\n";
    return;
  }
  if (gt.channels() != 1 || pair.left.size() != pair.right.size() ||
      gt.size() != pair.left.size()) {
    std::cerr << "disparity_bench: skipping " << name << ": unexpected sizes or channels\n";
    return;
  }
  gt.convertTo(pair.ground_truth, CV_32F, 1.0 / scale);
  pairs->push_back(pair);
}

void AddSynthetic(const attend::Scene& scene, const std::string& name, int frame, int max_disparity,
                  std::vector<Pair>* pairs) {
  const attend::SceneRenderer renderer(scene);
  const attend::RenderedFrame rendered = renderer.Render(frame);
  Pair pair;
  pair.name = name + " #" + std::to_string(frame);
  pair.source = "sequences/" + fs::path(scene.source).filename().string() + " frame " +
                std::to_string(frame) + (scene.width != 320 ? " at twice the size" : "");
  pair.left = rendered.left;
  pair.right = rendered.right;
  pair.ground_truth = rendered.disparity;
  pair.max_disparity = max_disparity;
  pairs->push_back(pair);
}

std::vector<Pair> LoadPairs(const Options& options, cv::Size* large_size) {
  std::vector<Pair> pairs;
  const fs::path root = fs::path(options.data_dir).lexically_normal();
  if (!fs::is_directory(root / "middlebury")) {
    std::cerr << "disparity_bench: skipping the Middlebury pairs: "
              << (root / "middlebury").string() << " not found\n";
  } else {
    AddMiddlebury(root, "middlebury", "tsukuba", "im3.png", "im4.png", "disp3.pgm", 16.0, 16,
                  &pairs);
    AddMiddlebury(root, "middlebury", "venus", "im2.png", "im6.png", "disp2.pgm", 8.0, 20,
                  &pairs);
    AddMiddlebury(root, "middlebury", "teddy", "im2.png", "im6.png", "disp2.png", 4.0, 60,
                  &pairs);
    AddMiddlebury(root, "middlebury", "cones", "im2.png", "im6.png", "disp2.png", 4.0, 60,
                  &pairs);
  }
  // Middlebury 2005 at third size: ground truth = value / 3, disparities up to about 76 px.
  if (!fs::is_directory(root / "middlebury2005")) {
    std::cerr << "disparity_bench: skipping the Middlebury 2005 pairs: "
              << (root / "middlebury2005").string() << " not found\n";
  } else {
    for (const char* name : {"Art", "Books", "Dolls", "Laundry", "Moebius", "Reindeer"}) {
      AddMiddlebury(root, "middlebury2005", name, "left.png", "right.png", "disp_left.png", 3.0,
                    80, &pairs);
    }
  }
  const std::string lab_path = options.home + "/sequences/lab.yaml";
  const std::string occlusions_path = options.home + "/sequences/occlusions.yaml";
  try {
    const attend::Scene lab = attend::LoadScene(lab_path);
    for (const int frame : kLabFrames) AddSynthetic(lab, "lab", frame, kSynthMaxDisparity, &pairs);
    const attend::Scene occlusions = attend::LoadScene(occlusions_path);
    for (const int frame : kOcclusionFrames) {
      AddSynthetic(occlusions, "occlusions", frame, kSynthMaxDisparity, &pairs);
    }
    const attend::Scene large = attend::bench::Doubled(lab);
    *large_size = cv::Size(large.width, large.height);
    AddSynthetic(large, "lab 640x480", kLargeFrame, kLargeMaxDisparity, &pairs);
  } catch (const std::exception& e) {
    std::cerr << "disparity_bench: skipping the synthetic pairs: " << e.what() << "\n";
  }
  return pairs;
}

// OpenCV's CV_16SC1 output in 1/16 px to pixels; invalid pixels (below minDisparity 0) -1.
cv::Mat FromFixedPoint(const cv::Mat& fixed) {
  cv::Mat disparity(fixed.size(), CV_32FC1);
  for (int y = 0; y < fixed.rows; ++y) {
    const int16_t* in = fixed.ptr<int16_t>(y);
    float* out = disparity.ptr<float>(y);
    for (int x = 0; x < fixed.cols; ++x) out[x] = in[x] < 0 ? -1.f : in[x] / 16.f;
  }
  return disparity;
}

// OpenCV's map with every invalid pixel filled by the estimator's own rule, the one its
// left-right check uses: the smaller of the nearest valid disparities to its left and right on
// its row (rows without a valid pixel become 0).
cv::Mat FillFromRow(const cv::Mat& disparity) {
  cv::Mat filled = disparity.clone();
  attend::FillInvalidDisparities(&filled);
  return filled;
}

// The ground truth without the pixels that the right view cannot see, derived from the left
// ground truth alone: a pixel whose match x - d lies outside the right image, or whose match
// is covered by a pixel further right landing left of it or within half a pixel of it (a
// nearer surface), becomes unknown.
cv::Mat NonOccluded(const cv::Mat& ground_truth) {
  cv::Mat visible = ground_truth.clone();
  for (int y = 0; y < ground_truth.rows; ++y) {
    const float* d = ground_truth.ptr<float>(y);
    float* out = visible.ptr<float>(y);
    float leftmost = std::numeric_limits<float>::infinity();  // min over x' > x of x' - d(x')
    for (int x = ground_truth.cols - 1; x >= 0; --x) {
      if (!(d[x] > 0.f) || !std::isfinite(d[x])) continue;
      const float match = static_cast<float>(x) - d[x];
      if (match < 0.f || leftmost < match + 0.5f) out[x] = 0.f;
      leftmost = std::min(leftmost, match);
    }
  }
  return visible;
}

// The number of pixels with known ground truth, and their largest disparity.
int CountKnown(const cv::Mat& ground_truth, double* largest = nullptr) {
  int known = 0;
  float max = 0.f;
  for (int y = 0; y < ground_truth.rows; ++y) {
    const float* d = ground_truth.ptr<float>(y);
    for (int x = 0; x < ground_truth.cols; ++x) {
      if (!(d[x] > 0.f) || !std::isfinite(d[x])) continue;
      ++known;
      max = std::max(max, d[x]);
    }
  }
  if (largest != nullptr) *largest = max;
  return known;
}

// One method on one pair: Run() is the timed call; Disparity() converts its last output to
// pixels (CV_32FC1, invalid < 0).
struct Method {
  std::string name;
  bool opencv = false;
  std::function<void()> run;
  std::function<cv::Mat()> disparity;
  std::vector<double> ms;
};

// Our option sets: the defaults, the thesis's settings, and the options on top of the defaults.
struct Variant {
  std::string name;
  attend::DisparityOptions options;
};

const std::vector<Variant>& Variants() {
  static const std::vector<Variant> variants = [] {
    std::vector<Variant> v;
    attend::DisparityOptions defaults;
    v.push_back({"ours", defaults});
    attend::DisparityOptions eight = defaults;
    eight.sgm_paths = 8;
    v.push_back({"ours sgm 8 paths", eight});
    attend::DisparityOptions subpixel = defaults;
    subpixel.subpixel = true;
    v.push_back({"ours --subpixel", subpixel});
    // The defaults before semi-global matching, which the attention loop keeps.
    attend::DisparityOptions hard = defaults;
    hard.smoothness = attend::DisparitySmoothness::kHard;
    hard.window = 7;
    hard.median = 0;
    v.push_back({"ours hard (window 7, lr-check)", hard});
    attend::DisparityOptions thesis = hard;
    thesis.window = 9;
    thesis.left_right_check = false;
    v.push_back({"ours thesis (hard, window 9, no lr-check)", thesis});
    attend::DisparityOptions penalty = hard;
    penalty.smoothness = attend::DisparitySmoothness::kPenalty;
    v.push_back({"ours smoothness=penalty (window 7)", penalty});
    return v;
  }();
  return variants;
}

std::vector<Method> MakeMethods(const Pair& pair) {
  std::vector<Method> methods;
  for (const Variant& variant : Variants()) {
    attend::DisparityOptions options = variant.options;
    options.max_disparity = pair.max_disparity;
    auto estimator = std::make_shared<attend::DisparityEstimator>(options);
    auto output = std::make_shared<cv::Mat>();
    methods.push_back(
        {variant.name,
         false,
         [estimator, output, &pair] { estimator->Compute(pair.left, pair.right, output.get()); },
         [output] { return output->clone(); },
         {}});
  }

  const int disparities = OpenCvDisparities(pair.max_disparity);
  cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(disparities, kBmBlockSize);
  bm->setPreFilterCap(kBmPreFilterCap);
  bm->setTextureThreshold(kBmTextureThreshold);
  bm->setUniquenessRatio(kBmUniquenessRatio);
  bm->setSpeckleWindowSize(kSpeckleWindowSize);
  bm->setSpeckleRange(kSpeckleRange);
  bm->setDisp12MaxDiff(kDisp12MaxDiff);
  auto grey = std::make_shared<std::pair<cv::Mat, cv::Mat>>();
  auto bm_output = std::make_shared<cv::Mat>();
  methods.push_back({"OpenCV StereoBM",
                     true,
                     [bm, grey, bm_output, &pair] {
                       cv::cvtColor(pair.left, grey->first, cv::COLOR_BGR2GRAY);
                       cv::cvtColor(pair.right, grey->second, cv::COLOR_BGR2GRAY);
                       bm->compute(grey->first, grey->second, *bm_output);
                     },
                     [bm_output] { return FromFixedPoint(*bm_output); },
                     {}});

  for (const int channels : {1, 3}) {
    cv::Ptr<cv::StereoSGBM> sgbm = attend::bench::MakeStereoSgbm(pair.max_disparity, channels);
    auto sgbm_grey = std::make_shared<std::pair<cv::Mat, cv::Mat>>();
    auto output = std::make_shared<cv::Mat>();
    methods.push_back({channels == 1 ? "OpenCV StereoSGBM" : "OpenCV StereoSGBM on BGR",
                       true,
                       [sgbm, sgbm_grey, output, channels, &pair] {
                         if (channels == 3) {
                           sgbm->compute(pair.left, pair.right, *output);
                           return;
                         }
                         cv::cvtColor(pair.left, sgbm_grey->first, cv::COLOR_BGR2GRAY);
                         cv::cvtColor(pair.right, sgbm_grey->second, cv::COLOR_BGR2GRAY);
                         sgbm->compute(sgbm_grey->first, sgbm_grey->second, *output);
                       },
                       [output] { return FromFixedPoint(*output); },
                       {}});
  }
  return methods;
}

// The accuracy of one disparity map; shares of the known ground-truth pixels.
struct Accuracy {
  double invalid = 0.0;
  attend::BadPixelRates all;
  attend::BadPixelRates non_occluded;
};

Accuracy Evaluate(const cv::Mat& disparity, const cv::Mat& ground_truth,
                  const cv::Mat& non_occluded) {
  Accuracy accuracy;
  accuracy.all = attend::EvaluateDisparity(disparity, ground_truth);
  accuracy.non_occluded = attend::EvaluateDisparity(disparity, non_occluded);
  int invalid = 0;
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const float* t = ground_truth.ptr<float>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      if (t[x] > 0.f && std::isfinite(t[x]) && !(d[x] >= 0.f && std::isfinite(d[x]))) ++invalid;
    }
  }
  accuracy.invalid =
      accuracy.all.known > 0 ? static_cast<double>(invalid) / accuracy.all.known : 0.0;
  return accuracy;
}

struct Row {
  std::string method;
  double ms = 0.0;
  bool opencv = false;
  Accuracy raw;     // invalid counted as bad
  Accuracy filled;  // OpenCV: invalid filled from the row; ours: the same as raw
};

// OpenCV's StereoSGBM at its best over a small grid of its parameters on one pair (bad1 of the
// filled map, all known pixels).
struct GridBest {
  double bad1 = 1.0;
  std::string parameters;
  int settings = 0;
};

struct PairResult {
  const Pair* pair = nullptr;
  GridBest grid;  // Middlebury pairs only
  int known = 0;
  int non_occluded = 0;
  double max_truth = 0.0;
  std::vector<Row> rows;
  std::string failure;
};

PairResult RunPair(const Pair& pair, int repeat) {
  PairResult result;
  result.pair = &pair;
  const cv::Mat non_occluded = NonOccluded(pair.ground_truth);
  result.known = CountKnown(pair.ground_truth, &result.max_truth);
  result.non_occluded = CountKnown(non_occluded);
  try {
    std::vector<Method> methods = MakeMethods(pair);
    for (Method& method : methods) method.run();  // warm-up: buffers, caches
    for (int round = 0; round < repeat; ++round) {
      for (Method& method : methods) {
        const attend::Stopwatch watch;
        method.run();
        method.ms.push_back(watch.ElapsedMs());
      }
    }
    for (Method& method : methods) {
      Row row;
      row.method = method.name;
      row.opencv = method.opencv;
      row.ms = Median(method.ms);
      const cv::Mat disparity = method.disparity();
      row.raw = Evaluate(disparity, pair.ground_truth, non_occluded);
      row.filled = method.opencv ? Evaluate(FillFromRow(disparity), pair.ground_truth, non_occluded)
                                 : row.raw;
      result.rows.push_back(row);
    }
  } catch (const std::exception& e) {
    result.failure = e.what();
    result.rows.clear();
  }
  return result;
}

// The grid: blockSize 3, 5, 7, 9 and (P1, P2) = (a, b) x blockSize^2 for (a, b) in (2, 16),
// (4, 32), (8, 32) (OpenCV's recommendation, disparity_bench's SGBM row at block 5), (4, 64),
// (8, 64), (16, 64); the other parameters as the SGBM row. Not timed.
GridBest SgbmGrid(const Pair& pair) {
  GridBest best;
  cv::Mat left, right, fixed;
  cv::cvtColor(pair.left, left, cv::COLOR_BGR2GRAY);
  cv::cvtColor(pair.right, right, cv::COLOR_BGR2GRAY);
  const std::vector<std::pair<int, int>> penalties = {{2, 16}, {4, 32}, {8, 32},
                                                      {4, 64}, {8, 64}, {16, 64}};
  for (const int block : {3, 5, 7, 9}) {
    for (const auto& [a, b] : penalties) {
      const int area = block * block;
      cv::Ptr<cv::StereoSGBM> sgbm =
          attend::bench::MakeStereoSgbm(pair.max_disparity, block, a * area, b * area);
      sgbm->compute(left, right, fixed);
      const double bad1 = attend::EvaluateDisparity(FillFromRow(FromFixedPoint(fixed)),
                                                    pair.ground_truth)
                              .bad1;
      ++best.settings;
      if (bad1 < best.bad1) {
        best.bad1 = bad1;
        best.parameters = "block " + std::to_string(block) + ", P1 " + std::to_string(a * area) +
                          ", P2 " + std::to_string(b * area);
      }
    }
  }
  return best;
}

std::string Percent(double share) { return Fixed(100.0 * share, 2); }

std::string Ratio(double numerator, double denominator) {
  return denominator > 0.0 ? Fixed(numerator / denominator, 2) : "n/a";
}

const Row* FindRow(const PairResult& result, const std::string& method) {
  for (const Row& row : result.rows) {
    if (row.method == method) return &row;
  }
  return nullptr;
}

bool IsMiddlebury(const Pair& pair) { return pair.source.rfind("Middlebury ", 0) == 0; }

// Bytes held by the estimator after one Compute on `pair` with each option set.
struct MemoryRow {
  std::string options;
  size_t bytes = 0;
};

std::vector<MemoryRow> MeasureMemory(const Pair& pair) {
  std::vector<MemoryRow> rows;
  for (const Variant& variant : Variants()) {
    attend::DisparityOptions options = variant.options;
    options.max_disparity = pair.max_disparity;
    attend::DisparityEstimator estimator(options);
    cv::Mat disparity;
    estimator.Compute(pair.left, pair.right, &disparity);
    rows.push_back({variant.name, estimator.buffer_bytes()});
  }
  return rows;
}

void WriteReport(const Options& options, const std::vector<PairResult>& results, const Pair* large,
                 const std::vector<MemoryRow>& memory, std::ostream& out) {
  const attend::DisparityOptions defaults;
  out << "Date: " << UtcNow() << "; CPU: " << CpuModel()
      << "; nproc: " << std::thread::hardware_concurrency() << "; OpenCV " << CV_VERSION
      << "; cv::getNumThreads() = " << cv::getNumThreads() << "; repetitions: " << options.repeat
      << " (median, after one warm-up round; the methods take turns, one call each per "
         "round).\n\n";
  out << "Ours: DisparityEstimator with its defaults (smoothness "
      << attend::DisparitySmoothnessName(defaults.smoothness) << ", " << defaults.sgm_paths
      << " paths, P1 " << defaults.sgm_p1 << ", P2 " << defaults.sgm_p2 << ", median "
      << defaults.median << ", window " << defaults.window << ", lr_tolerance "
      << defaults.lr_tolerance << ")"
      << ", disparities 0..D-1, on the BGR pair (grey conversion inside, timed). OpenCV: "
         "numDisparities = D rounded up to a multiple of 16 (OpenCV requires it; the range "
         "searched is then 0..numDisparities-1), minDisparity 0, grey conversion of both views "
         "timed with the call. StereoBM: blockSize "
      << kBmBlockSize << ", preFilterCap " << kBmPreFilterCap << ", textureThreshold "
      << kBmTextureThreshold << ", uniquenessRatio " << kBmUniquenessRatio
      << ". StereoSGBM (MODE_SGBM): blockSize " << kSgbmBlockSize << ", P1 = 8 cn blockSize^2, "
      << "P2 = 32 cn blockSize^2 (cn = 1 on grey, 3 on BGR), preFilterCap " << kSgbmPreFilterCap
      << ", uniquenessRatio " << kSgbmUniquenessRatio << ". Both: speckleWindowSize "
      << kSpeckleWindowSize << ", speckleRange " << kSpeckleRange << ", disp12MaxDiff "
      << kDisp12MaxDiff << ".\n\n";
  out << "bad1, bad2: share of the pixels with known ground truth where |d - d_gt| > 1 px, "
         "> 2 px (SPEC 4), invalid pixels counted as bad. invalid: share of those pixels "
         "without a disparity. OpenCV rows appear twice: as computed (invalid = bad) and "
         "filled (every invalid pixel takes the smaller of the nearest valid disparities on "
         "its row, left and right, by attend::FillInvalidDisparities, the fill of our "
         "--lr-check; a row without a valid pixel becomes 0). non-occ: the same over the pixels "
         "the right view sees, "
         "derived from the left ground truth (a pixel is occluded when its match x - d lies "
         "outside the right image or when a pixel to its right lands left of its match or "
         "within half a pixel of it).\n\n";

  out << "### Pairs\n\n";
  out << "| pair | source | size | known px | non-occ px | max GT disparity | D ours | D OpenCV "
         "|\n";
  out << "|---|---|---|---:|---:|---:|---:|---:|\n";
  for (const PairResult& r : results) {
    const Pair& p = *r.pair;
    out << "| " << p.name << " | " << p.source << " | " << p.left.cols << "x" << p.left.rows
        << " | " << r.known << " | " << r.non_occluded << " | " << Fixed(r.max_truth, 2) << " | "
        << p.max_disparity << " | " << OpenCvDisparities(p.max_disparity) << " |\n";
  }

  out << "\n### All methods (percentages)\n\n";
  out << "| pair | method | ms | invalid | bad1 | bad2 | bad1 non-occ | bad2 non-occ |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const PairResult& r : results) {
    if (!r.failure.empty()) {
      out << "| " << r.pair->name << " | failed: " << r.failure << " | | | | | | |\n";
      continue;
    }
    for (const Row& row : r.rows) {
      const auto line = [&](const std::string& label, const Accuracy& a) {
        out << "| " << r.pair->name << " | " << label << " | " << Fixed(row.ms, 1) << " | "
            << Percent(a.invalid) << " | " << Percent(a.all.bad1) << " | " << Percent(a.all.bad2)
            << " | " << Percent(a.non_occluded.bad1) << " | " << Percent(a.non_occluded.bad2)
            << " |\n";
      };
      line(row.method, row.raw);
      if (row.opencv) line(row.method + ", filled", row.filled);
    }
  }

  out << "\n### Ours (defaults) against OpenCV, filled (bad1 in %, all known pixels)\n\n";
  out << "| pair | size | D | ours ms | BM ms | SGBM ms | SGBM / ours time | ours bad1 | BM bad1 "
         "| SGBM bad1 | SGBM on BGR bad1 | ours / BM bad1 | ours / SGBM bad1 |\n";
  out << "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const PairResult& r : results) {
    const Row* ours = FindRow(r, "ours");
    const Row* bm = FindRow(r, "OpenCV StereoBM");
    const Row* sgbm = FindRow(r, "OpenCV StereoSGBM");
    const Row* sgbm_bgr = FindRow(r, "OpenCV StereoSGBM on BGR");
    if (ours == nullptr || bm == nullptr || sgbm == nullptr || sgbm_bgr == nullptr) continue;
    const Pair& p = *r.pair;
    out << "| " << p.name << " | " << p.left.cols << "x" << p.left.rows << " | " << p.max_disparity
        << " | " << Fixed(ours->ms, 1) << " | " << Fixed(bm->ms, 1) << " | " << Fixed(sgbm->ms, 1)
        << " | " << Ratio(sgbm->ms, ours->ms) << "x | " << Percent(ours->raw.all.bad1) << " | "
        << Percent(bm->filled.all.bad1) << " | " << Percent(sgbm->filled.all.bad1) << " | "
        << Percent(sgbm_bgr->filled.all.bad1) << " | "
        << Ratio(ours->raw.all.bad1, bm->filled.all.bad1) << " | "
        << Ratio(ours->raw.all.bad1, sgbm->filled.all.bad1) << " |\n";
  }

  // Issue 29: bad1 below StereoSGBM's, its defaults and its best of the grid, on every
  // Middlebury pair, at no more than its time on one core.
  {
    out << "\n### Ours (defaults) against StereoSGBM's defaults and its best of a grid, "
           "Middlebury (bad1 in %, all known pixels, SGBM filled)\n\n";
    out << "| pair | ours bad1 | SGBM bad1 | SGBM best of grid bad1 | its parameters | below "
           "SGBM | below its best | ours ms | SGBM ms | ours / SGBM time |\n";
    out << "|---|---:|---:|---:|---|---|---|---:|---:|---:|\n";
    int pairs = 0, below = 0, below_best = 0, not_slower = 0;
    double time_ratio = 0.0, worst_ratio = 0.0;
    for (const PairResult& r : results) {
      if (!IsMiddlebury(*r.pair)) continue;
      const Row* ours = FindRow(r, "ours");
      const Row* sgbm = FindRow(r, "OpenCV StereoSGBM");
      if (ours == nullptr || sgbm == nullptr || r.grid.settings == 0) continue;
      const double ratio = ours->ms / sgbm->ms;
      const bool wins = ours->raw.all.bad1 < sgbm->filled.all.bad1;
      const bool wins_best = ours->raw.all.bad1 < r.grid.bad1;
      ++pairs;
      below += wins;
      below_best += wins_best;
      not_slower += ratio <= 1.0;
      time_ratio += ratio;
      worst_ratio = std::max(worst_ratio, ratio);
      out << "| " << r.pair->name << " | " << Percent(ours->raw.all.bad1) << " | "
          << Percent(sgbm->filled.all.bad1) << " | " << Percent(r.grid.bad1) << " | "
          << r.grid.parameters << " (best of " << r.grid.settings << ") | "
          << (wins ? "yes" : "no") << " | " << (wins_best ? "yes" : "no") << " | "
          << Fixed(ours->ms, 1) << " | " << Fixed(sgbm->ms, 1) << " | " << Fixed(ratio, 2)
          << " |\n";
    }
    if (pairs > 0) {
      out << "\nbad1 below SGBM's on " << below << " of " << pairs << " pairs, below its best of "
          << "the grid on " << below_best << " of " << pairs << "; ours took at most SGBM's time "
          << "on " << not_slower << " of " << pairs << " pairs, " << Fixed(time_ratio / pairs, 2)
          << " of it on average (the most: " << Fixed(worst_ratio, 2) << ").\n";
    }
  }

  // SPEC 5: faster than StereoSGBM at the same size and range; more accurate than StereoBM on
  // the Middlebury pairs, with SGBM's accuracy as the goal.
  out << "\n### SPEC 5 by option set (pairs where ours wins)\n\n";
  out << "| options | faster than SGBM, all pairs | bad1 below BM as computed, Middlebury | bad1 "
         "below BM filled, Middlebury | bad1 below SGBM filled, Middlebury |\n";
  out << "|---|---:|---:|---:|---:|\n";
  for (const Variant& v : Variants()) {
    const char* variant = v.name.c_str();
    int compared = 0, faster = 0, middlebury = 0, below_bm = 0, below_bm_filled = 0, below_sgbm = 0;
    for (const PairResult& r : results) {
      const Row* ours = FindRow(r, variant);
      const Row* bm = FindRow(r, "OpenCV StereoBM");
      const Row* sgbm = FindRow(r, "OpenCV StereoSGBM");
      if (ours == nullptr || bm == nullptr || sgbm == nullptr) continue;
      ++compared;
      if (ours->ms < sgbm->ms) ++faster;
      if (!IsMiddlebury(*r.pair)) continue;
      ++middlebury;
      if (ours->raw.all.bad1 < bm->raw.all.bad1) ++below_bm;
      if (ours->raw.all.bad1 < bm->filled.all.bad1) ++below_bm_filled;
      if (ours->raw.all.bad1 < sgbm->filled.all.bad1) ++below_sgbm;
    }
    const auto of = [](int count, int total) {
      return std::to_string(count) + " of " + std::to_string(total);
    };
    out << "| " << variant << " | " << of(faster, compared) << " | " << of(below_bm, middlebury)
        << " | " << of(below_bm_filled, middlebury) << " | " << of(below_sgbm, middlebury)
        << " |\n";
  }

  // The SPEC 5 accuracy target is on the mean over the Middlebury pairs.
  out << "\n### Mean bad1 (all known pixels) over the Middlebury pairs, and time relative to "
         "SGBM\n\n";
  out << "| method | mean bad1 % | mean of (ms / SGBM ms) |\n|---|---:|---:|\n";
  std::vector<std::string> names;
  for (const Variant& v : Variants()) names.push_back(v.name);
  names.push_back("OpenCV StereoBM");
  names.push_back("OpenCV StereoSGBM");
  for (const std::string& name : names) {
    double bad = 0.0, time = 0.0;
    int count = 0;
    for (const PairResult& r : results) {
      if (!IsMiddlebury(*r.pair)) continue;
      const Row* row = FindRow(r, name.c_str());
      const Row* sgbm = FindRow(r, "OpenCV StereoSGBM");
      if (row == nullptr || sgbm == nullptr) continue;
      const bool opencv = name.rfind("OpenCV", 0) == 0;
      bad += opencv ? row->filled.all.bad1 : row->raw.all.bad1;
      time += row->ms / sgbm->ms;
      ++count;
    }
    if (count == 0) continue;
    out << "| " << name << (name.rfind("OpenCV", 0) == 0 ? " (filled)" : "") << " | "
        << Fixed(100.0 * bad / count, 2) << " | " << Fixed(time / count, 2) << " |\n";
  }

  if (large != nullptr && !memory.empty()) {
    out << "\n### Estimator buffers at " << large->left.cols << "x" << large->left.rows
        << ", D = " << large->max_disparity << " (" << large->source << ")\n\n";
    out << "| options | buffer_bytes | MB |\n|---|---:|---:|\n";
    for (const MemoryRow& row : memory) {
      out << "| " << row.options << " | " << row.bytes << " | "
          << Fixed(static_cast<double>(row.bytes) / (1024.0 * 1024.0), 1) << " |\n";
    }
    out << "\nSPEC 5 target: under 128 MB (MB = 2^20 bytes here).\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  options.data_dir = ATTEND_SOURCE_ROOT "/../shared/data";
  options.home = ATTEND_SOURCE_ROOT;
  options.repeat = 7;
  const int status = attend::bench::ParseBenchOptions(
      "disparity_bench", "disparity against StereoBM and StereoSGBM (docs/DISPARITY.md)",
      "reference data folder holding middlebury/; pairs that are missing are skipped", argc, argv,
      &options);
  if (status >= 0) return status;
  cv::setNumThreads(1);

  cv::Size large_size;
  const std::vector<Pair> pairs = LoadPairs(options, &large_size);
  if (pairs.empty()) {
    std::cerr << "disparity_bench: no pairs to run\n";
    return 1;
  }
  std::vector<PairResult> results;
  const Pair* large = nullptr;
  for (const Pair& pair : pairs) {
    std::cerr << "disparity_bench: " << pair.name << " (" << pair.left.cols << "x" << pair.left.rows
              << ", D " << pair.max_disparity << ")\n";
    results.push_back(RunPair(pair, options.repeat));
    if (IsMiddlebury(pair)) results.back().grid = SgbmGrid(pair);
    if (!results.back().failure.empty()) {
      std::cerr << "disparity_bench: " << pair.name << " failed: " << results.back().failure
                << "\n";
    }
    if (pair.left.size() == large_size) large = &pair;
  }
  std::vector<MemoryRow> memory;
  if (large != nullptr) {
    try {
      memory = MeasureMemory(*large);
    } catch (const std::exception& e) {
      std::cerr << "disparity_bench: buffer measurement failed: " << e.what() << "\n";
    }
  }

  std::ostringstream report;
  WriteReport(options, results, large, memory, report);
  std::cout << report.str();
  if (!options.markdown_path.empty()) {
    std::ofstream file(options.markdown_path);
    file << report.str();
    if (!file) {
      std::cerr << "disparity_bench: cannot write " << options.markdown_path << "\n";
      return 1;
    }
  }
  return 0;
}
