// Every options struct with a Check(): its defaults are valid, and Check() is able to refuse
// (one broken field each), so a default moved out of its own range fails here, not in a run.
#include <gtest/gtest.h>

#include "colour/skin_model.h"
#include "features/centre_surround.h"
#include "features/motion.h"
#include "features/skin.h"
#include "io/sequence.h"
#include "pipeline/attend_options.h"
#include "pyramid/bip.h"
#include "pyramid/segmentation.h"
#include "saliency/saliency.h"
#include "semiattentive/attention.h"
#include "stereo/disparity.h"
#include "synth/render_sequence.h"
#include "tracker/target_tracker.h"
#include "tracker/tracker.h"

namespace attend {
namespace {

// The defaults pass; the struct with `breaks` applied does not.
template <typename Options, typename Break>
void ExpectDefaultsValid(const char* name, Break breaks) {
  const Options defaults;
  EXPECT_EQ(defaults.Check(), "") << name;
  Options broken;
  breaks(&broken);
  EXPECT_NE(broken.Check(), "") << name << ": Check() accepts a broken field";
}

TEST(OptionDefaults, EveryOptionsStructsDefaultsPassItsCheck) {
  ExpectDefaultsValid<SequenceOptions>("SequenceOptions",
                                       [](SequenceOptions* o) { o->stride = 0; });
  ExpectDefaultsValid<BipOptions>("BipOptions", [](BipOptions* o) { o->max_levels = 0; });
  ExpectDefaultsValid<SegmentationOptions>("SegmentationOptions",
                                           [](SegmentationOptions* o) { o->t_max = -1.f; });
  ExpectDefaultsValid<DisparityOptions>("DisparityOptions",
                                        [](DisparityOptions* o) { o->window = 4; });
  ExpectDefaultsValid<TrackerOptions>("TrackerOptions", [](TrackerOptions* o) { o->alpha = 0.f; });
  ExpectDefaultsValid<OpenCvTrackerOptions>("OpenCvTrackerOptions",
                                            [](OpenCvTrackerOptions* o) { o->lost_frames = 0; });
  ExpectDefaultsValid<TargetTrackerOptions>("TargetTrackerOptions",
                                            [](TargetTrackerOptions* o) { o->bip.alpha = 2.f; });
  ExpectDefaultsValid<SkinModel>("SkinModel", [](SkinModel* o) { o->threshold = 0.0; });
  ExpectDefaultsValid<SkinRegionOptions>("SkinRegionOptions",
                                         [](SkinRegionOptions* o) { o->min_area = 0; });
  ExpectDefaultsValid<MotionOptions>("MotionOptions", [](MotionOptions* o) { o->rate = 0.0; });
  ExpectDefaultsValid<CentreSurroundOptions>("CentreSurroundOptions",
                                             [](CentreSurroundOptions* o) { o->surround = -1.0; });
  ExpectDefaultsValid<SaliencyOptions>("SaliencyOptions",
                                       [](SaliencyOptions* o) { o->blur = -1.0; });
  ExpectDefaultsValid<AttentionOptions>("AttentionOptions",
                                        [](AttentionOptions* o) { o->select.min_saliency = 2.f; });
  ExpectDefaultsValid<OutputOptions>("OutputOptions",
                                     [](OutputOptions* o) { o->dump = {"overlay", "overlay"}; });
  ExpectDefaultsValid<SynthOptions>("SynthOptions", [](SynthOptions* o) { o->threads = -1; });
}

}  // namespace
}  // namespace attend
