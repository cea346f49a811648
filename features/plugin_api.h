// The entry point of out-of-tree feature plugins (docs/PLUGINS.md). A plugin is a shared
// library that exports one C function, `attend_plugin`, returning a description of itself:
// the ABI version it was built against and a function that registers its features.
//
//   #include "features/plugin_api.h"
//   static void Register(attend::FeatureRegistry* registry) {
//     registry->Add("my_feature", "what it measures", &CreateMyFeature);
//   }
//   ATTEND_PLUGIN("my_plugin", Register)
//
// `attend` loads the libraries named in `plugins:` at start, checks the ABI version and calls
// the register function; any failure is a configuration error (exit status 2) naming the file.
// The version changes whenever what a plugin sees changes in a way that breaks binary
// compatibility: FeatureMap and SequenceStart (features/feature_map.h), FeatureRegistry,
// FeatureSetup, the FrameContext interface (features/frame_context.h), Segmentation,
// RegionStats and RegionAdjacency (pyramid/regions.h), SkinModel (colour/skin_model.h),
// CylinderColour (colour/colour.h), DisparityOptions (stereo/disparity.h), NormalisationRegistry
// (saliency/normalisation.h), ParamBlock (config/param_block.h), the field tables
// (util/option_fields.h, config/read_fields.h) and Range (util/range.h). Nothing of the pyramid
// or the pipeline is in that list.
// Version 2: the context became an interface, and FeatureMap got BeginSequence and
// EndSequence. Version 3: the context gives the disparity. Version 4: the context gives where
// attention looks (AttentionRegions), and a FeatureMap may report detections (Detection).
// Version 5: the region adjacency became plain vectors (RegionAdjacency, no Boost in the plugin
// API), and every normalisation is in one registry (FeatureRegistry::normalisations()).
// Version 6: a FeatureMap may report the pixels its detector searched (searched_pixels).
// Version 7: a FeatureMap says whether it reads AttentionRegions (ReadsAttentionRegions).
//
// A plugin reads its parameters as the built-in features do: an options struct with a field
// table, read with ReadFields (config/read_fields.h; examples/temporal_change). The
// ParamBlock getters (GetInt, GetDouble, ...) stay part of the ABI, for plugins built before.
#pragma once

#include "features/feature_map.h"

#define ATTEND_PLUGIN_ABI_VERSION 7

extern "C" {

struct AttendPluginInfo {
  int abi_version;    // ATTEND_PLUGIN_ABI_VERSION of the headers the plugin was built with
  const char* name;   // the plugin library's name, for messages
  void (*register_features)(attend::FeatureRegistry* registry);
};

// The one symbol attend looks up.
typedef const AttendPluginInfo* (*AttendPluginEntry)();

}  // extern "C"

#define ATTEND_PLUGIN_ENTRY_SYMBOL "attend_plugin"

// Defines the entry point of a plugin library.
#define ATTEND_PLUGIN(NAME, REGISTER_FUNCTION)                                      \
  extern "C" __attribute__((visibility("default"))) const AttendPluginInfo*         \
  attend_plugin() {                                                                 \
    static const AttendPluginInfo info{ATTEND_PLUGIN_ABI_VERSION, NAME,             \
                                       REGISTER_FUNCTION};                          \
    return &info;                                                                   \
  }
