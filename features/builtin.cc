#include "features/builtin.h"

#include "features/centre_bias.h"
#include "features/centre_surround.h"
#include "features/contrast.h"
#include "features/detectors.h"
#include "features/disparity_feature.h"
#include "features/motion.h"
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
  registry.Add("disparity",
               "stereo disparity, nearer is more salient: box-filtered ZNCC and Sun's two-stage "
               "dynamic programming (thesis 5.1.1)",
               &CreateDisparityFeature);
  registry.Add("motion",
               "luminance change against the previous frames, less global brightness change "
               "and sensor noise (not in the thesis)",
               &CreateMotionFeature);
  registry.Add("centre_bias",
               "a Gaussian centred on the image: where people look in photographs (not in the "
               "thesis)",
               &CreateCentreBiasFeature);
  registry.Add("centre_surround",
               "Lab colour and lightness contrast at several scales, as centre-surround "
               "differences of Gaussians (Itti et al. 1998; not in the thesis)",
               &CreateCentreSurroundFeature);
  registry.Add("people",
               "boxes of the people OpenCV's HOG pedestrian detector finds, where attention looks "
               "or in the whole frame (top-down; not in the thesis)",
               &CreatePeopleFeature);
  registry.Add("faces",
               "boxes of the faces a cascade classifier finds, where attention looks or in the "
               "whole frame (top-down; not in the thesis)",
               &CreateFacesFeature);
  return registry;
}

}  // namespace attend
