// attend run: the attention pipeline over a sequence (SPEC 3.2, 3.3).
#include <unistd.h>

#include <csignal>
#include <iostream>
#include <memory>

#include "app/run_attention.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "pipeline/options_doc.h"
#include "pipeline/options_io.h"
#include "util/error.h"

namespace attend {

namespace {

// Set by the first Ctrl-C; a signal handler can only reach global state.
std::atomic<bool> g_stop_requested{false};

// The signal that asked the run to stop (SIGINT or SIGTERM), 0 when none did.
std::atomic<int> g_stop_signal{0};

extern "C" void OnStopSignal(int signal) {
  g_stop_signal.store(signal);
  g_stop_requested.store(true);
  std::signal(signal, SIG_DFL);  // a second one stops at once
}

struct RunArguments {
  std::string config;
  SourceSpec source;  // --sequence ... --gst-right, --side-by-side-live
  double duration = -1.0;
  std::string out;
  bool overwrite = false;
  std::vector<std::string> sets;
  std::string frames;
  bool quiet = false;
  bool list_keys = false;
  std::string command_line;
};

int Run(const RunArguments& args) {
  if (args.list_keys) {
    std::cout << "The configuration's keys (configs/README.md): type, range, default and what "
                 "each does.\n"
              << FormatFieldDescriptions(DescribeEveryKey());
    return 0;
  }
  AttentionRunRequest request;
  request.config = args.config;
  request.sets = args.sets;
  request.source = args.source;
  request.frames = args.frames;
  request.duration_s = args.duration;
  if (!args.quiet) {
    request.on_left_out = [](const std::string& name) {
      std::cerr << "attend: note: feature '" << name
                << "' needs stereo and is left out: the source is monocular (the shipped "
                   "configuration; a configuration of your own must disable it)\n";
    };
  }
  request.out = args.out;
  request.overwrite = args.overwrite;
  request.quiet = args.quiet;
  request.command_line = args.command_line;
  request.stop = &g_stop_requested;
  const bool show_progress = !args.quiet && isatty(STDERR_FILENO);
  if (show_progress) request.on_progress = PrintRunProgress;
  const AttendOptions options = ResolveRunOptions(request);

  std::signal(SIGINT, OnStopSignal);
  std::signal(SIGTERM, OnStopSignal);
  RunSummary summary;
  try {
    summary = RunAttention(request, options);
  } catch (...) {
    if (show_progress) std::cerr << "\n";
    throw;
  }
  if (show_progress) std::cerr << "\n";
  // A live source that stopped delivering ended the run: said even with --quiet, since the
  // run is shorter than asked for.
  if (summary.live.has_value() && summary.live->end == LiveEnd::kTimeout) {
    std::cerr << "attend: warning: " << summary.live->why << "; the run ends with the "
              << summary.frames << (summary.frames == 1 ? " frame" : " frames") << " it had\n";
  }
  if (!args.quiet) std::cout << summary.BriefReport() << std::endl;
  // Stopped by a signal: the run is complete up to its last frame, but not done. Exit as the
  // shell does for a killed command (128 + signal), so scripts can tell.
  if (summary.interrupted && g_stop_signal.load() != 0) return 128 + g_stop_signal.load();
  return 0;
}

constexpr const char* kSequenceHelp =
    "Sequence folder with left/ and right/ (or only left/); or KITTI's own layouts as unpacked: "
    "a raw drive folder (DATE/DATE_drive_NNNN_sync) or a tracking sequence's "
    "training/image_02/NNNN (docs/SEQUENCES.md)";

}  // namespace

void AddRunCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<RunArguments>();
  CLI::App* run = app.add_subcommand(
      "run",
      "Run the attention pipeline over a sequence, a video or a live camera or GStreamer "
      "pipeline and write a run folder (SPEC 3.3). With no source it runs on the bundled "
      "sequence. On a monocular source the shipped configuration leaves its stereo features "
      "(disparity) out with a note.");
  run->add_option("--config", args->config,
                  "Configuration YAML (default: configs/default.yaml of the attend home)");
  auto* seq = run->add_option("--sequence", args->source.folder, kSequenceHelp);
  auto* left = run->add_option("--left", args->source.left_video, "Left video of a pair");
  auto* right = run->add_option("--right", args->source.right_video, "Right video of a pair");
  auto* sbs = run->add_option("--side-by-side", args->source.side_by_side_video,
                              "Side-by-side stereo video");
  auto* video = run->add_option("--video", args->source.video, "Monocular video");
  auto* images = run->add_option(
      "--images", args->source.images,
      "Monocular plain folder of frames (.png .jpg .jpeg .ppm .pgm, sorted by name)");
  auto* camera = run->add_option("--camera", args->source.camera,
                                 "Live V4L2 camera /dev/videoN (docs/LIVE.md)")
                     ->type_name("N")
                     ->check(FiniteRange(0, 4095));
  auto* camera_right =
      run->add_option("--camera-right", args->source.camera_right,
                      "Right camera of a live stereo pair (with --camera or --gst)")
          ->type_name("M")
          ->check(FiniteRange(0, 4095));
  auto* gst = run->add_option(
      "--gst", args->source.gst,
      "Live GStreamer pipeline, read through OpenCV; it should end in an appsink (' ! "
      "videoconvert ! appsink' is appended when it names none): 'v4l2src ! videoconvert ! "
      "appsink', 'videotestsrc is-live=true'");
  gst->type_name("PIPELINE");
  auto* gst_right = run->add_option("--gst-right", args->source.gst_right,
                                    "Right pipeline of a live stereo pair (with --camera or --gst)")
                        ->type_name("PIPELINE");
  run->add_flag("--side-by-side-live", args->source.live.side_by_side,
                "The live source's frames hold the left view in their left half and the right "
                "view in their right half (live.side_by_side)");
  run->add_option("--calib", args->source.calib,
                  "Stereo calibration (calib.yaml as attend calibrate writes it; "
                  "docs/STEREO3D.md): a raw pair is rectified on the fly; wins over SEQ/calib.yaml "
                  "(sequence.calib)")
      ->type_name("FILE");
  run->add_option("--duration", args->duration,
                  "Live sources: stop capturing S seconds after the first frame "
                  "(live.duration_s); the frames queued are still processed")
      ->type_name("S")
      ->check(FiniteRange(0.0, 1e7));
  left->needs(right);
  right->needs(left);
  seq->excludes(left, right, sbs, video, images, camera, camera_right, gst, gst_right);
  left->excludes(sbs, video, images, camera, camera_right, gst, gst_right);
  right->excludes(images, camera, camera_right, gst, gst_right);
  sbs->excludes(video, images, camera, camera_right, gst, gst_right);
  video->excludes(images, camera, camera_right, gst, gst_right);
  images->excludes(camera, camera_right, gst, gst_right);
  camera->excludes(gst);
  camera_right->excludes(gst_right);
  run->add_option("--out", args->out,
                  "Run folder (default: runs/<date>-<time>-<config>-<sequence>)");
  run->add_flag("--overwrite", args->overwrite, "Replace a previous run in a non-empty --out");
  AddSetOption(run, &args->sets,
               "Override a configuration key, the value parsed as YAML: --set select.max_new=3, "
               "--set 'output.dump=[overlay]', --set features.skin.weight=0.5; --list-keys "
               "lists the keys");
  run->add_flag("--list-keys", args->list_keys,
                "Print every configuration key with its type, range, default and a line of doc, and exit");
  run->add_option("--frames", args->frames,
                  "Frame range FIRST:LAST, inclusive (10:50, 10:, :99); for a live source the "
                  "numbers count the frames read from it, so :99 ends after the 100th");
  run->add_flag("--quiet", args->quiet,
                "No progress line, report or notes; errors, and the warning that a live source "
                "stopped, only");
  args->command_line = command_line;
  run->callback([args, action] { *action = [args] { return Run(*args); }; });
}

ATTEND_COMMAND(10, "run", AddRunCommand);

}  // namespace attend
