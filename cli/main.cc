// attend: visual attention on stereo image sequences. See README.md and SPEC 3.2.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <malloc.h>
#include <string_view>
#include <iostream>
#include <opencv2/core/utils/logger.hpp>

#include "cli/commands.h"
#include "util/error.h"
#include "util/strings.h"

namespace {

// 0 when every argument may be used, else the exit status after the error is printed.
int CheckArguments(int argc, char** argv) {
  // Paths and values from the command line go into config.yaml, summary.json and the other
  // records, which are UTF-8 text: bytes that are not UTF-8 would be written as U+FFFD and
  // name a file that does not exist, so that the run could not be read back. They are
  // refused, with the bytes shown as \xNN.
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument(argv[i]);
    const size_t bad = attend::InvalidUtf8At(argument);
    if (bad == std::string_view::npos) continue;
    std::string shown;
    for (const unsigned char c : argument) {
      if (c >= 0x20 && c < 0x7f) {
        shown += static_cast<char>(c);
      } else {
        char escaped[8];
        std::snprintf(escaped, sizeof(escaped), "\\x%02X", c);
        shown += escaped;
      }
    }
    std::cerr << "attend: error: argument " << i << " ('" << shown << "') is not valid UTF-8 "
              << "(byte " << bad << "): attend records paths and values in UTF-8 JSON and YAML, "
              << "where these bytes cannot be written so that they read back; rename the file "
              << "or folder\n";
    return static_cast<int>(attend::ExitStatus::kUsage);
  }

  // An empty argument is never meant: `--video "$VIDEO"` with VIDEO unset would otherwise
  // fall back to the bundled sequence (or the current folder) and exit 0.
  for (int i = 1; i < argc; ++i) {
    const std::string_view argument(argv[i]);
    const bool empty_value = argument.size() > 2 && argument.substr(0, 2) == "--" &&
                             argument.back() == '=';
    if (!argument.empty() && !empty_value) continue;
    std::string what = "argument " + std::to_string(i);
    if (empty_value) {
      what += " (" + std::string(argument.substr(0, argument.size() - 1)) + ")";
    } else if (i > 1 && argv[i - 1][0] == '-') {
      what += " (the value of " + std::string(argv[i - 1]) + ")";
    }
    std::cerr << "attend: error: " << what << " is empty: an empty path or value is never "
              << "meant (is a shell variable unset?)\n";
    return static_cast<int>(attend::ExitStatus::kUsage);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // attend reports its own errors, naming the file; OpenCV's backend chatter (GStreamer,
  // image-sequence probing) would only bury them.
  // OpenCV reads its log level at start-up, so it is set here directly; a user who sets
  // OPENCV_LOG_LEVEL keeps theirs.
  if (std::getenv("OPENCV_LOG_LEVEL") == nullptr) {
    cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  }
  // GStreamer reads live pipelines (--gst, cv::CAP_GSTREAMER), but a video file is left to it
  // only after every other backend refused it: 1 is the lowest priority (0 would turn the
  // backend off, and --gst with it).
  setenv("OPENCV_VIDEOIO_PRIORITY_GSTREAMER", "1", 0);
  // One malloc arena for the whole process. attend's threads keep their buffers from frame to
  // frame and allocate little while they run, so they do not contend for it, and a second
  // arena for the thread that works on the next frame (pipeline/run.cc) held 3-4 MB more at
  // 640x480 (docs/PERFORMANCE.md, "Two frames at once"). MALLOC_ARENA_MAX, when set, wins.
  if (std::getenv("MALLOC_ARENA_MAX") == nullptr) mallopt(M_ARENA_MAX, 1);

  const int bad_arguments = CheckArguments(argc, argv);
  if (bad_arguments != 0) return bad_arguments;
  CLI::App app{"attend: visual attention on stereo image sequences (Bounded Irregular Pyramid)"};
  app.set_version_flag("--version", std::string("attend ") + ATTEND_VERSION);
  app.require_subcommand(1);

  std::string command_line = "attend";
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];
  attend::CommandAction action;
  attend::AddCommands(app, command_line, &action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "attend: error: " << e.what() << "\n";
    const CLI::App* failing = app.get_subcommands().empty() ? &app : app.get_subcommands().front();
    std::cerr << "Run '"
              << (failing == &app ? std::string("attend") : "attend " + failing->get_name())
              << " --help' for the options.\n";
    return static_cast<int>(attend::ExitStatus::kUsage);
  }

  try {
    return action();
  } catch (const attend::Error& e) {
    std::cerr << "attend: error: " << e.what() << "\n";
    return static_cast<int>(e.status());
  } catch (const std::exception& e) {
    std::cerr << "attend: error: internal: " << e.what() << "\n";
    return static_cast<int>(attend::ExitStatus::kInternal);
  }
}
