#include "cli/home.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "synth/render_sequence.h"
#include "synth/scene.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {

namespace {

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

std::string AttendHome() {
  const char* home = std::getenv("ATTEND_HOME");
  return home != nullptr && *home != '\0' ? home : ATTEND_SOURCE_ROOT;
}

std::string DefaultConfigPath() {
  return (fs::path(AttendHome()) / "configs" / "default.yaml").string();
}

std::string EnsureBundledSequence(bool quiet) {
  const fs::path scene_path = fs::path(AttendHome()) / "sequences" / "lab.yaml";
  const fs::path target = fs::path(AttendHome()) / "sequences" / "generated" / "lab";
  const std::string scene_text = ReadText(scene_path);
  if (scene_text.empty()) {
    throw ConfigError(scene_path.string() + ": the bundled scene is missing (set ATTEND_HOME to " +
                      "the attend source folder)");
  }
  // The copy of the scene beside the frames tells whether they are current.
  if (fs::exists(target / "left") && ReadText(target / "scene.yaml") == scene_text) {
    return target.string();
  }
  if (!quiet)
    std::cerr << "[attend] rendering the bundled sequence into " << target.string() << "\n";
  const Scene scene = LoadScene(scene_path.string());
  // Render beside the target and rename into place, so that a concurrent run never reads a
  // half-written sequence.
  const fs::path temporary = target.string() + ".tmp-" + std::to_string(getpid());
  std::error_code ignored;
  fs::remove_all(temporary, ignored);
  RenderSequence(scene, temporary.string(), SynthOptions{});
  std::ofstream(temporary / "scene.yaml") << scene_text;
  fs::remove_all(target, ignored);
  fs::rename(temporary, target, ignored);
  fs::remove_all(temporary, ignored);  // another process won the race: its copy is as good
  return target.string();
}

}  // namespace attend
