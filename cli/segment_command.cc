// attend segment: BIP colour segmentation of still images, with the quality measures of
// thesis 3.3.2 on request (SPEC 3.2, docs/PYRAMID.md).
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/segment_images.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "app/home.h"
#include "pipeline/options_io.h"
#include "util/strings.h"

namespace attend {

namespace {

struct SegmentArguments {
  std::vector<std::string> images;
  std::string out;
  std::string config;
  std::vector<std::string> sets;
  bool metrics = false;
  bool quiet = false;
};

int Segment(const SegmentArguments& args) {
  const std::string config_path = args.config.empty() ? SegmentConfigPath() : args.config;
  SegmentRequest request;
  request.options = LoadOptions(config_path, args.sets).segmentation;
  request.stems = OutputStems(args.images, "outputs STEM.*.png");
  request.images = args.images;
  request.out = args.out;
  request.metrics = args.metrics;
  SegmentImages(request, [&args](const SegmentedImage& image) {
    if (args.quiet) return;
    std::string line = image.path + ": " + std::to_string(image.regions) + " regions, " +
                       std::to_string(image.pyramid_levels) + " levels, " +
                       Fixed(image.milliseconds, 1) + " ms";
    if (image.quality) {
      line += ", F " + Fixed(image.quality->f, 4) + ", Q " + Fixed(image.quality->q, 4);
      line += image.shift_variance ? ", SV " + Fixed(*image.shift_variance, 3)
                                   : std::string(", SV n/a (image too small)");
    }
    std::cout << line << std::endl;
  });
  return 0;
}

}  // namespace

void AddSegmentCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<SegmentArguments>();
  CLI::App* segment = app.add_subcommand(
      "segment",
      "Segment images with the Bounded Irregular Pyramid (docs/PYRAMID.md). Every image is read "
      "as 8-bit BGR: grey images become three equal channels and 16-bit images are scaled to 8 "
      "bits. For each IMAGE writes OUT/<stem>.labels.png (16-bit region labels), "
      "OUT/<stem>.regions.png (false colour) and OUT/<stem>.mean.png (region mean colours), then "
      "OUT/segment.json. OUT may already hold other files: only these named files are written "
      "(and replaced).");
  segment->add_option("IMAGE", args->images, "Images to segment (their stems must differ)")
      ->required();
  segment->add_option("--out", args->out, "Output folder, created if missing")->required();
  segment->add_option("--config", args->config,
                      "Configuration YAML; its segmentation block is used (default: "
                      "configs/segment.yaml of the attend home, the merge by spread; "
                      "configs/default.yaml holds the attention loop's thesis regions)");
  AddSetOption(segment, &args->sets,
               "Override a configuration key, the value parsed as YAML: "
               "--set segmentation.t_max=30 (repeatable)");
  segment->add_flag("--metrics", args->metrics,
                    "Also compute F, Q and the shift variance (thesis 3.3.2; smaller is better)");
  segment->add_flag("--quiet", args->quiet, "No line per image; errors only");
  segment->callback([args, action] { *action = [args] { return Segment(*args); }; });
}

ATTEND_COMMAND(30, "segment", AddSegmentCommand);

}  // namespace attend
