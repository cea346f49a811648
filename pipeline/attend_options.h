// The options of the whole program, one struct per module, as read from the YAML
// configuration (SPEC 3.4). Only pipeline/options_io.cc binds them to YAML.
#pragma once

#include <string>
#include <vector>

#include "config/feature_list.h"
#include "io/sequence.h"
#include "pyramid/segmentation.h"

namespace attend {

// What `attend run` writes besides config.yaml, frames.jsonl and summary.json.
struct OutputOptions {
  // Run folder; "" makes runs/<date>-<time>-<config>-<sequence> below the current folder.
  std::string dir;
  // Per-frame dumps (SPEC 3.3); each must be one of DumpKinds().
  std::vector<std::string> dump = {"overlay"};
  // Also write the overlays as RUN/overlay.avi (Motion-JPEG).
  bool video = false;

  // The dumps this build can write.
  static const std::vector<std::string>& DumpKinds();
  // Empty when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  bool Dumps(const std::string& kind) const;
};

struct AttendOptions {
  SequenceOptions sequence;
  OutputOptions output;
  // The BIP colour segmentation of each frame (and of `attend segment`).
  SegmentationOptions segmentation;
  // Feature plugins with their weights and own parameters (SPEC 2.3, 3.4).
  std::vector<FeatureSpec> features;
  // Out-of-tree plugin libraries loaded at start.
  std::vector<std::string> plugins;
};

}  // namespace attend
