#include "features/builtin.h"

#include "features/contrast.h"
#include "features/skin.h"

namespace attend {

FeatureRegistry BuiltinFeatures() {
  FeatureRegistry registry;
  registry.Add("colour_contrast", "mean colour gradient of each BIP colour region (thesis eq. 5.1)",
               &CreateColourContrast);
  registry.Add("intensity_contrast",
               "mean intensity gradient of each BIP colour region (thesis eq. 5.2)",
               &CreateIntensityContrast);
  registry.Add("skin", "TSL skin chrominance within a Mahalanobis threshold (thesis 5.1.1)",
               &CreateSkinFeature);
  // "disparity" (thesis 5.1.1, SPEC 2.3) joins this list with the stereo estimator.
  return registry;
}

}  // namespace attend
