// A plugin whose map has one NaN pixel from the second frame on: attend must stop the run as
// the plugin's failure (exit status 4), naming the feature and the pixel.
#include <limits>

#include "features/plugin_api.h"

namespace {

class NotFinite : public attend::FeatureMap {
 public:
  void Compute(const attend::FrameContext& context, cv::Mat* out) override {
    out->create(context.size(), CV_32FC1);
    out->setTo(0.5f);
    if (frames_++ > 0) out->at<float>(10, 20) = std::numeric_limits<float>::quiet_NaN();
  }

 private:
  int frames_ = 0;
};

void Register(attend::FeatureRegistry* registry) {
  registry->Add("not_finite", "a map with a NaN pixel from the second frame on (a test plugin)",
                [](const attend::ParamBlock&, const attend::FeatureSetup&) {
                  return std::unique_ptr<attend::FeatureMap>(new NotFinite());
                });
}

}  // namespace

ATTEND_PLUGIN("not_finite", Register)
