// The options of the whole program, one struct per module, as read from the YAML
// configuration (SPEC 3.4). Only pipeline/options_io.cc binds them to YAML.
#pragma once

#include <string>
#include <vector>

#include "config/feature_list.h"
#include "io/sequence.h"
#include "pyramid/segmentation.h"
#include "saliency/saliency.h"
#include "semiattentive/attention.h"

namespace attend {

// What `attend run` writes besides config.yaml, frames.jsonl and summary.json.
struct OutputOptions {
  // Run folder; "" makes runs/<date>-<time>-<config>-<sequence> below the current folder.
  std::string dir;
  // Per-frame dumps (SPEC 3.3); each must be one of DumpKinds().
  std::vector<std::string> dump = {"overlay"};
  // Files written for each dumped float map (saliency, features): "pfm" the map itself
  // (lossless), "png" an 8-bit preview of its normalised values.
  std::vector<std::string> map_formats = {"pfm", "png"};
  // Also write the overlays as RUN/overlay.avi (Motion-JPEG).
  bool video = false;

  // The dumps this build can write.
  static const std::vector<std::string>& DumpKinds();
  static const std::vector<std::string>& MapFormats();
  // Empty when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  bool Dumps(const std::string& kind) const;
  bool WritesMapFormat(const std::string& format) const;
  // The fields (util/option_fields.h): the output section's keys.
  static const OptionFields<OutputOptions>& Fields();
};

struct AttendOptions {
  SequenceOptions sequence;
  OutputOptions output;
  // The BIP colour segmentation of each frame (and of `attend segment`).
  SegmentationOptions segmentation;
  // Feature plugins with their weights and own parameters (SPEC 2.3, 3.4).
  std::vector<FeatureSpec> features;
  // How the feature maps become the saliency map.
  SaliencyOptions saliency;
  // The semi-attentive stage: selection, release, inhibition and the trackers.
  AttentionOptions attention;
  // Out-of-tree plugin libraries loaded at start.
  std::vector<std::string> plugins;
  // Threads for the stages that can share a frame's work (the feature plugins): 0 = one per
  // core, 1 = everything on the calling thread. Results do not depend on it.
  int threads = 0;
  // The top-level keys plugins and threads (the sections have their structs' tables).
  static const OptionFields<AttendOptions>& Fields();
};

}  // namespace attend
