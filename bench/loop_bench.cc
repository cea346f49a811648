// Benchmark (SPEC 5, issue 28): the whole attention loop as `attend run` runs it, one process a
// run, against OpenCV's StereoSGBM timed in the same rounds as a yardstick of the machine's
// speed, and the loop's peak resident set. Prints a markdown report; docs/PERFORMANCE.md holds
// one with its command.
//
//   loop_bench [--home DIR] [--repeat N] [--markdown FILE] [--attend PATH] [--frames N]
//
// Sequences: the bundled lab scene (sequences/lab.yaml) rendered at 320x240, and the same scene
// rendered at twice its size (640x480, every length doubled), into a temporary folder.
// Runs (default configuration, no dumps, `--set threads=T`):
//   320x240, D = 32, threads 1 and 2;
//   640x480, D = 64, threads 1 and 2 (the 640x480 rendering);
//   640x480 from 320x240, D = 64, threads 1: the 320x240 files scaled up by the working size,
//     as docs/PERFORMANCE.md measured the loop at 640x480 before (cheaper to read).
// In each round every run goes once, the order reversed every other round, and StereoSGBM
// (grey conversion of both views + compute, MODE_SGBM, blockSize 5, P1 = 8 * 25, P2 = 32 * 25,
// as disparity_bench; one thread) on four frame pairs of each size just before the runs of
// that size. A run's time a frame is its summary.json's wall time over its frames (reading,
// every stage and writing the records); its peak resident set is the child's ru_maxrss. The
// report gives medians over the rounds of the time a frame and of the ratio to SGBM's median
// call in the same round, and the largest resident set.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "bench/bench_scenes.h"
#include "bench/sgbm_peer.h"
#include "synth/render_sequence.h"
#include "synth/scene.h"
#include "util/subprocess.h"
#include "util/timer.h"

namespace {

namespace fs = std::filesystem;
using attend::bench::Fixed;
using attend::bench::Median;

constexpr int kSgbmFrames[] = {0, 40, 80, 110};

// One size's sequence and its SGBM yardstick.
struct Size {
  std::string name;      // "320x240"
  std::string sequence;  // the rendered sequence folder
  int max_disparity = 0;
  std::vector<std::pair<cv::Mat, cv::Mat>> pairs;  // BGR frames for SGBM
  std::vector<double> sgbm_ms;                     // per round: the median call
};

// One configuration of `attend run`.
struct Run {
  std::string name;
  int size = 0;  // index into the sizes
  int threads = 1;
  std::vector<std::string> sets;  // extra --set words
  std::vector<double> frame_ms;   // per round
  std::vector<double> ratio;      // per round: frame_ms / that round's SGBM call
  long peak_rss_kb = 0;
  nlohmann::json stages;  // the last round's timings_ms
};

double SgbmCallMs(const Size& size) {
  cv::Ptr<cv::StereoSGBM> sgbm = attend::bench::MakeStereoSgbm(size.max_disparity, 1);
  std::vector<double> times;
  cv::Mat left, right, disparity;
  for (const auto& [left_bgr, right_bgr] : size.pairs) {
    const attend::Stopwatch watch;
    cv::cvtColor(left_bgr, left, cv::COLOR_BGR2GRAY);
    cv::cvtColor(right_bgr, right, cv::COLOR_BGR2GRAY);
    sgbm->compute(left, right, disparity);
    times.push_back(watch.ElapsedMs());
  }
  return Median(times);
}

// Runs `attend run` for `run`; returns false (with the reason in `error`) when it failed.
bool RunAttend(const std::string& attend, const Size& size, const fs::path& work, Run* run,
               double* frame_ms, std::string* error) {
  const fs::path out = work / "run";
  std::vector<std::string> argv = {attend,        "run",
                                   "--sequence",  size.sequence,
                                   "--out",       out.string(),
                                   "--overwrite", "--quiet",
                                   "--set",       "threads=" + std::to_string(run->threads),
                                   "--set",       "output.dump=[]"};
  for (const std::string& set : run->sets) {
    argv.push_back("--set");
    argv.push_back(set);
  }
  const std::string err = (work / "run.err").string();
  const pid_t pid = attend::StartProcess(argv, (work / "run.out").string(), err, error);
  if (pid < 0) return false;
  const attend::ProcessExit exit = attend::WaitProcess(pid);
  if (exit.Status() != 0) {
    std::ifstream in(err);
    std::stringstream text;
    text << in.rdbuf();
    *error = attend::ShellQuote(argv) + " ended with status " + std::to_string(exit.Status()) +
             ": " + text.str();
    return false;
  }
  run->peak_rss_kb = std::max(run->peak_rss_kb, exit.peak_rss_kb);
  std::ifstream summary_file(out / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const double frames = summary.at("frames").get<double>();
  *frame_ms = 1000.0 * summary.at("wall_seconds").get<double>() / std::max(1.0, frames);
  run->stages = summary.at("timings_ms");
  return true;
}

std::string Mib(long kb) { return Fixed(kb / 1024.0, 1); }
std::string Mb(long kb) { return Fixed(kb * 1024.0 / 1e6, 1); }

}  // namespace

int main(int argc, char** argv) {
  attend::bench::BenchOptions options;
  options.home = ATTEND_SOURCE_ROOT;
  options.repeat = 5;
  std::string attend = ATTEND_BINARY;
  int frames = 120;
  // Parsed by hand around the shared options: --attend PATH and --frames N are this bench's.
  std::vector<char*> shared = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--attend" || arg == "--frames") && i + 1 < argc) {
      if (arg == "--attend")
        attend = argv[++i];
      else
        frames = std::atoi(argv[++i]);
    } else {
      shared.push_back(argv[i]);
    }
  }
  const int parsed = attend::bench::ParseBenchOptions(
      "loop_bench",
      "the attention loop (attend run) against StereoSGBM, and its peak resident set; also "
      "--attend PATH (default: the build's attend) and --frames N (default 120)",
      "unused", static_cast<int>(shared.size()), shared.data(), &options);
  if (parsed >= 0) return parsed;
  if (frames < 10 || frames > 120) {
    std::cerr << "loop_bench: --frames must be in 10..120\n";
    return 2;
  }
  cv::setNumThreads(1);

  const fs::path work =
      fs::temp_directory_path() / ("attend-loop-bench-" + std::to_string(getpid()));
  fs::create_directories(work);
  std::vector<Size> sizes(2);
  try {
    const attend::Scene lab = attend::LoadScene(options.home + "/sequences/lab.yaml");
    attend::SynthOptions synth;
    synth.frames = frames;
    sizes[0] = {"320x240", (work / "lab320").string(), 32, {}, {}};
    sizes[1] = {"640x480", (work / "lab640").string(), 64, {}, {}};
    attend::RenderSequence(lab, sizes[0].sequence, synth);
    attend::RenderSequence(attend::bench::Doubled(lab), sizes[1].sequence, synth);
    for (Size& size : sizes) {
      for (const int frame : kSgbmFrames) {
        if (frame >= frames) continue;
        char name[32];
        std::snprintf(name, sizeof(name), "%06d.png", frame);
        size.pairs.emplace_back(cv::imread(size.sequence + "/left/" + name),
                                cv::imread(size.sequence + "/right/" + name));
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "loop_bench: cannot render the lab scene: " << e.what() << "\n";
    fs::remove_all(work);
    return 1;
  }

  const std::vector<std::string> large = {"sequence.width=640", "sequence.height=480",
                                          "features.disparity.max_disparity=64"};
  std::vector<Run> runs = {
      {"320x240, D = 32, 1 thread", 0, 1, {}, {}, {}, 0, {}},
      {"320x240, D = 32, 2 threads", 0, 2, {}, {}, {}, 0, {}},
      {"640x480, D = 64, 1 thread", 1, 1, large, {}, {}, 0, {}},
      {"640x480, D = 64, 2 threads", 1, 2, large, {}, {}, 0, {}},
      {"640x480 from 320x240 files, D = 64, 1 thread", 0, 1, large, {}, {}, 0, {}},
  };
  // Runs of a size after that size's SGBM; the 640x480-from-320x240 run is compared with the
  // 640x480 SGBM (the size it computes at).
  auto sgbm_size = [](const Run& run) { return run.sets.empty() ? run.size : 1; };

  for (int round = 0; round <= options.repeat; ++round) {  // round 0 warms up
    std::vector<int> order = {0, 1};
    if (round % 2 == 1) std::reverse(order.begin(), order.end());
    std::vector<double> sgbm(sizes.size());
    for (const int s : order) {
      sgbm[s] = SgbmCallMs(sizes[s]);
      for (Run& run : runs) {
        if (sgbm_size(run) != s) continue;
        double frame_ms = 0.0;
        std::string error;
        if (!RunAttend(attend, sizes[run.size], work, &run, &frame_ms, &error)) {
          std::cerr << "loop_bench: " << run.name << ": " << error << "\n";
          fs::remove_all(work);
          return 1;
        }
        if (round > 0) {
          run.frame_ms.push_back(frame_ms);
          run.ratio.push_back(frame_ms / sgbm[s]);
        }
      }
    }
    if (round > 0) {
      for (size_t s = 0; s < sizes.size(); ++s) sizes[s].sgbm_ms.push_back(sgbm[s]);
    }
    std::cerr << "loop_bench: round " << round << " of " << options.repeat << " done\n";
  }
  fs::remove_all(work);

  std::ostringstream out;
  out << "# The attention loop against StereoSGBM\n\n"
      << "`" << options.command_line << "`, " << attend::bench::UtcNow() << ", "
      << attend::bench::CpuModel() << ", " << options.repeat << " rounds after a warm-up, "
      << frames << " frames of the lab scene a run (default configuration, no dumps).\n\n";
  out << "| size | StereoSGBM call, ms (median of rounds) |\n|---|---:|\n";
  for (const Size& size : sizes) {
    out << "| " << size.name << ", D = " << size.max_disparity << " | "
        << Fixed(Median(size.sgbm_ms), 2) << " |\n";
  }
  out << "\n| run | ms a frame | frames/s | SGBM calls a frame | peak resident set, MiB (MB) |\n"
      << "|---|---:|---:|---:|---:|\n";
  for (const Run& run : runs) {
    const double ms = Median(run.frame_ms);
    out << "| " << run.name << " | " << Fixed(ms, 2) << " | " << Fixed(1000.0 / ms, 1) << " | "
        << Fixed(Median(run.ratio), 2) << " | " << Mib(run.peak_rss_kb) << " ("
        << Mb(run.peak_rss_kb) << ") |\n";
  }
  out << "\nStage means of the last round, ms a frame (summary.json's timings_ms; with 2 threads "
         "`read`, `segment` and `features` of frame t + 1 run beside `saliency`, `track`, "
         "`inhibit` and `select` of frame t):\n\n";
  std::vector<std::string> stages;
  for (const auto& [key, value] : runs[0].stages.items()) {
    if (key.rfind("feature.", 0) != 0 || key == "feature.disparity") stages.push_back(key);
  }
  out << "| run |";
  for (const std::string& stage : stages) out << " " << stage << " |";
  out << "\n|---|";
  for (size_t i = 0; i < stages.size(); ++i) out << "---:|";
  out << "\n";
  for (const Run& run : runs) {
    out << "| " << run.name << " |";
    for (const std::string& stage : stages) {
      out << " " << (run.stages.contains(stage) ? Fixed(run.stages[stage].get<double>(), 2) : "")
          << " |";
    }
    out << "\n";
  }
  // The bars of issue 47 (and SPEC 5's memory).
  const double ratio320 = Median(runs[0].ratio);
  const double fps640 = 1000.0 / Median(runs[2].frame_ms);
  const double fps640_two = 1000.0 / Median(runs[3].frame_ms);
  const long rss640 = std::max(runs[2].peak_rss_kb, runs[3].peak_rss_kb);
  out << "\n| bar | measured | met |\n|---|---:|---|\n"
      << "| 320x240, 1 thread: at most 1.0 SGBM call a frame | " << Fixed(ratio320, 2) << " | "
      << (ratio320 <= 1.0 ? "yes" : "no") << " |\n"
      << "| 640x480, D = 64, 1 thread: at least 40 frames/s | " << Fixed(fps640, 1) << " | "
      << (fps640 >= 40.0 ? "yes" : "no") << " |\n"
      << "| 640x480, D = 64, 2 threads: at least 55 frames/s | " << Fixed(fps640_two, 1) << " | "
      << (fps640_two >= 55.0 ? "yes" : "no") << " |\n"
      << "| 640x480, D = 64: peak resident set under 128 MB (SPEC 5) | " << Mb(rss640) << " MB | "
      << (rss640 * 1024.0 < 128e6 ? "yes" : "no") << " |\n";
  std::cout << out.str();
  if (!options.markdown_path.empty()) {
    std::ofstream file(options.markdown_path);
    file << out.str();
  }
  return 0;
}
