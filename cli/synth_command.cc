// attend synth: render a stereo sequence with ground truth from a scene description.
#include <iostream>
#include <memory>

#include "app/render_scene.h"
#include "cli/commands.h"

namespace attend {

namespace {

struct SynthArguments {
  std::string scene;
  std::string out;
  std::int64_t seed = -1;
  int frames = -1;
  bool overwrite = false;
  bool quiet = false;
};

int Synth(const SynthArguments& args) {
  RenderSceneRequest request;
  request.scene = args.scene;
  request.out = args.out;
  if (args.seed >= 0) request.seed = static_cast<std::uint64_t>(args.seed);
  if (args.frames >= 0) request.frames = args.frames;
  request.overwrite = args.overwrite;
  const RenderSceneResult result = RenderScene(request);
  if (!args.quiet) {
    std::cout << result.summary.BriefReport() << " in " << static_cast<int>(result.milliseconds)
              << " ms\n";
  }
  return 0;
}

}  // namespace

void AddSynthCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<SynthArguments>();
  CLI::App* synth = app.add_subcommand(
      "synth",
      "Render a stereo sequence with exact ground truth from a scene description "
      "(docs/SYNTH.md)");
  synth->add_option("SCENE", args->scene, "Scene description (YAML)")->required();
  synth->add_option("--out", args->out, "Sequence folder to write")->required();
  synth->add_option("--seed", args->seed, "Seed for textures and noise (default: the scene's)")
      ->check(CLI::NonNegativeNumber);
  synth->add_option("--frames", args->frames, "Number of frames (default: the scene's)")
      ->check(CLI::PositiveNumber);
  synth->add_flag("--overwrite", args->overwrite,
                  "Replace a sequence in a non-empty --out (other files are kept)");
  synth->add_flag("--quiet", args->quiet, "Print nothing but errors");
  synth->callback([args, action] { *action = [args] { return Synth(*args); }; });
}

ATTEND_COMMAND(20, "synth", AddSynthCommand);

}  // namespace attend
