#include "app/home.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "synth/render_sequence.h"
#include "synth/scene.h"
#include "util/error.h"
#include "util/strings.h"

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

std::string SegmentConfigPath() {
  return (fs::path(AttendHome()) / "configs" / "segment.yaml").string();
}

std::string TrackConfigPath(TrackerKind kind) {
  const char* file = TrackerKindOf(kind).config_file;
  if (file == nullptr) return "";
  return (fs::path(AttendHome()) / "configs" / file).string();
}

std::string EnsureBundledSequence(bool quiet) {
  const fs::path scene_path = fs::path(AttendHome()) / "sequences" / "lab.yaml";
  const std::string scene_text = ReadText(scene_path);
  if (scene_text.empty()) {
    throw ConfigError(scene_path.string() + ": the bundled scene is missing (set ATTEND_HOME to " +
                      "the attend source folder)");
  }
  // One folder per version of the scene file (FNV-1a of its text): a changed scene renders
  // into a new folder, and a folder in use by another run is never touched.
  const uint64_t hash = Fnv1a(scene_text);
  char version[20];
  std::snprintf(version, sizeof(version), "%016llx", static_cast<unsigned long long>(hash));
  const fs::path target =
      fs::path(AttendHome()) / "sequences" / "generated" / (std::string("lab-") + version);
  if (fs::exists(target / "sequence.yaml")) return target.string();
  if (!quiet)
    std::cerr << "[attend] rendering the bundled sequence into " << target.string() << "\n";
  const Scene scene = LoadScene(scene_path.string());
  // Render beside the target and rename into place, so that a concurrent run never reads a
  // half-written sequence; if another process got there first, its copy is as good.
  const fs::path temporary = target.string() + ".tmp-" + std::to_string(getpid());
  std::error_code ignored;
  fs::remove_all(temporary, ignored);
  RenderSequence(scene, temporary.string(), SynthOptions{});
  std::ofstream(temporary / "scene.yaml") << scene_text;
  fs::rename(temporary, target, ignored);
  fs::remove_all(temporary, ignored);
  return target.string();
}

}  // namespace attend
