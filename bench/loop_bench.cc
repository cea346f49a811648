// The attention loop of `attend run` over frames held in memory: the yardstick of
// bench/python_bench.py (docs/PERFORMANCE.md, "The Python module"). Each frame goes through
// what RunSequence does with it (pipeline/run.cc), less the reading and the run folder: the
// pipeline, the record in input pixels and its JSON line. Prints one JSON object: the
// milliseconds a frame of each timed pass.
//
//   loop_bench [--config FILE] [--sequence SEQ] [--set KEY=VALUE]... [--passes N]
#include <CLI/CLI.hpp>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/home.h"
#include "app/run_attention.h"
#include "io/frame_record.h"
#include "io/sequence.h"
#include "pipeline/frame_pipeline.h"
#include "util/error.h"
#include "util/timer.h"

namespace attend {
namespace {

// One pass over `frames` with a new pipeline, as a run of the sequence: ms a frame.
double Pass(const AttendOptions& options, const FeatureRegistry& registry,
            const SequenceInfo& info, const std::vector<StereoFrame>& frames, size_t* bytes) {
  FeatureSetup setup;
  setup.stereo = info.stereo;
  setup.home = AttendHome();
  FramePipeline pipeline(options, registry, setup);
  const Stopwatch wall;
  pipeline.BeginSequence({info.name, info.size, info.stereo, options.sequence.first_frame});
  for (const StereoFrame& frame : frames) {
    FrameRecord record;
    record.frame = frame.index;
    pipeline.Process(frame, &record);
    const FrameRecord input =
        InputFromWorking(record, info.scale_x, info.scale_y, info.native_size);
    *bytes += FrameRecordToJson(input).size();
  }
  pipeline.EndSequence();
  return wall.ElapsedMs() / frames.size();
}

int Main(int argc, char** argv) {
  AttentionRunRequest request;
  int passes = 5;
  CLI::App app{"The attend run loop over frames held in memory (bench/python_bench.py)",
               "loop_bench"};
  app.add_option("--config", request.config, "configuration file (default: configs/default.yaml)");
  app.add_option("--sequence", request.source.folder, "sequence folder (default: bundled lab)");
  app.add_option("--set", request.sets, "KEY=VALUE override, as attend run --set");
  app.add_option("--passes", passes, "timed passes after one warm-up pass")
      ->check(CLI::Range(1, 1000));
  CLI11_PARSE(app, argc, argv);
  request.quiet = true;
  const AttendOptions options = ResolveRunOptions(request);
  std::unique_ptr<FrameSource> source = FrameSource::Open(options.sequence);
  const SequenceInfo info = source->info();
  std::vector<StereoFrame> frames;
  for (StereoFrame frame; source->Next(&frame);) frames.push_back(frame);
  if (frames.empty()) throw InputError("the sequence has no frames");
  if (options.threads > 0) cv::setNumThreads(options.threads);
  const FeatureRegistry registry = LoadFeatureRegistry(options.plugins);

  size_t bytes = 0;
  Pass(options, registry, info, frames, &bytes);  // warm-up
  nlohmann::json report;
  report["frames"] = frames.size();
  report["size"] = {info.size.width, info.size.height};
  report["ms_per_frame"] = nlohmann::json::array();
  for (int i = 0; i < passes; ++i) {
    report["ms_per_frame"].push_back(Pass(options, registry, info, frames, &bytes));
  }
  report["record_bytes"] = bytes;
  std::cout << report.dump() << std::endl;
  return 0;
}

}  // namespace
}  // namespace attend

int main(int argc, char** argv) {
  try {
    return attend::Main(argc, argv);
  } catch (const attend::Error& e) {
    std::cerr << "loop_bench: error: " << e.what() << std::endl;
    return static_cast<int>(e.status());
  }
}
