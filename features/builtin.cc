#include "features/builtin.h"

#include "features/centre_bias.h"
#include "features/centre_surround.h"
#include "features/contrast.h"
#include "features/detectors.h"
#include "features/dnn_detector.h"
#include "features/disparity_feature.h"
#include "features/motion.h"
#include "features/skin.h"

namespace attend {

namespace {

std::vector<FieldDescription> NoKeys() { return {}; }

// The descriptions of several tables, one after the other.
std::vector<FieldDescription> Joined(std::vector<FieldDescription> first,
                                     const std::vector<FieldDescription>& second) {
  first.insert(first.end(), second.begin(), second.end());
  return first;
}

std::vector<FieldDescription> DisparityKeys() {
  return Joined(DescribeFields(DisparityOptions::Fields()),
                DescribeFields(DisparityFeatureOptions::Fields()));
}

// The `backend` key and the dnn backend's keys, each marked as the dnn backend's.
std::vector<FieldDescription> BackendKeys(const OptionFields<ChannelBackend>& backend,
                                          const std::string& fallback, DnnDecoder decoder) {
  std::vector<FieldDescription> lines = DescribeFields(backend, ChannelBackend{fallback});
  for (FieldDescription line : DescribeFields(DnnDetectorOptions::Fields(),
                                              DnnDetectorOptions::ForDecoder(decoder))) {
    line.key = "dnn: " + line.key;
    lines.push_back(line);
  }
  return lines;
}

std::vector<FieldDescription> PeopleKeys() {
  return Joined(Joined(DescribeFields(HogPeopleOptions::Fields()),
                       DescribeFields(ObjectChannelOptions::Fields())),
                BackendKeys(ChannelBackend::PeopleFields(), "hog", DnnDecoder::kYolox));
}

std::vector<FieldDescription> FacesKeys() {
  return Joined(Joined(DescribeFields(FaceCascadeOptions::Fields()),
                       DescribeFields(ObjectChannelOptions::Fields(), FacesChannelDefaults())),
                BackendKeys(ChannelBackend::FacesFields(), "cascade", DnnDecoder::kYunet));
}

std::vector<FieldDescription> ObjectsKeys() {
  return Joined(Joined(DescribeFields(ChannelBackend::ObjectsFields(), ChannelBackend{"dnn"}),
                       DescribeFields(ObjectChannelOptions::Fields())),
                DescribeFields(DnnDetectorOptions::Fields()));
}

}  // namespace

// The built-in features' table. Adding a feature: CONTRIBUTING.md, "A feature map" (its file,
// and its row here).
const std::vector<BuiltinFeature>& BuiltinFeatureTable() {
  static const std::vector<BuiltinFeature> table = {
      {"colour_contrast", "mean colour gradient of each BIP colour region (thesis eq. 5.1)",
       &CreateColourContrast, &NoKeys},
      {"intensity_contrast", "mean intensity gradient of each BIP colour region (thesis eq. 5.2)",
       &CreateIntensityContrast, &NoKeys},
      {"skin", "TSL skin chrominance within a Mahalanobis threshold (thesis 5.1.1)",
       &CreateSkinFeature, [] { return DescribeFields(SkinFeatureOptions::Fields()); }},
      {"disparity",
       "stereo disparity (box-filtered ZNCC and Sun's two-stage dynamic programming, thesis "
       "5.1.1), scored as depth contrast against the surround and the ground, or as nearness",
       &CreateDisparityFeature, &DisparityKeys},
      {"motion",
       "luminance change against the previous frames, less global brightness change and "
       "sensor noise (not in the thesis)",
       &CreateMotionFeature, [] { return DescribeFields(MotionOptions::Fields()); }},
      {"centre_bias",
       "a Gaussian centred on the image: where people look in photographs (not in the thesis)",
       &CreateCentreBiasFeature, [] { return DescribeFields(CentreBiasOptions::Fields()); }},
      {"centre_surround",
       "Lab colour and lightness contrast at several scales, as centre-surround differences of "
       "Gaussians (Itti et al. 1998; not in the thesis)",
       &CreateCentreSurroundFeature,
       [] { return DescribeFields(CentreSurroundOptions::Fields()); }},
      {"people",
       "boxes of the people OpenCV's HOG pedestrian detector (or a network: backend dnn) finds, where attention looks or "
       "in the whole frame (top-down; not in the thesis)",
       &CreatePeopleFeature, &PeopleKeys},
      {"faces",
       "boxes of the faces a cascade classifier (or a network: backend dnn) finds, where attention looks or in the whole "
       "frame (top-down; not in the thesis)",
       &CreateFacesFeature, &FacesKeys},
      {"objects",
       "boxes of the objects of the classes asked for that a detector network (cv::dnn) finds, "
       "labelled with their class names (top-down; not in the thesis)",
       &CreateObjectsFeature, &ObjectsKeys}};
  return table;
}

FeatureRegistry BuiltinFeatures() {
  FeatureRegistry registry;
  for (const BuiltinFeature& feature : BuiltinFeatureTable()) {
    registry.Add(feature.name, feature.summary, feature.create);
  }
  return registry;
}

}  // namespace attend
