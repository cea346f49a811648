// An out-of-tree feature plugin for attend: temporal change. Where the left image changed
// since the previous frame, something moved or appeared, which draws attention (Itti's
// flicker channel). The map is the absolute difference of the luminance of consecutive frames,
// averaged over a `window` x `window` box; the first frame's map is zero.
//
// Build it with the project (it is built as build/examples/libattend_temporal_change.so) or on
// its own against attend's headers (docs/PLUGINS.md), then enable it in the configuration:
//   plugins: [build/examples/libattend_temporal_change.so]
//   features:
//     - {name: temporal_change, weight: 1.0, window: 5}
#include <opencv2/imgproc.hpp>

#include "config/read_fields.h"
#include "features/plugin_api.h"

namespace {

// The plugin's parameters, in a field table (util/option_fields.h): read with their ranges and
// errors at their lines by attend::ReadFields, like the built-in features'.
struct TemporalChangeOptions {
  int window = 5;  // side of the box, px, odd
  static const attend::OptionFields<TemporalChangeOptions>& Fields() {
    static const attend::OptionFields<TemporalChangeOptions> fields = {
        {"window", &TemporalChangeOptions::window, attend::Range::Closed(1, 101),
         "side of the box the change is averaged over, px, odd"}};
    return fields;
  }
};

class TemporalChange : public attend::FeatureMap {
 public:
  explicit TemporalChange(int window) : window_(window) {}

  // A new sequence starts afresh: its first frame has no previous one.
  void BeginSequence(const attend::SequenceStart&) override { previous_.release(); }

  // It never looks at where attention looked, so `attend run` with two threads may compute it
  // for the next frame while the attention stage finishes the current one.
  bool ReadsAttentionRegions() const override { return false; }

  void Compute(const attend::FrameContext& context, cv::Mat* out) override {
    cv::cvtColor(context.left(), luminance_, cv::COLOR_BGR2GRAY);
    luminance_.convertTo(current_, CV_32F);
    if (previous_.empty()) {
      out->create(current_.size(), CV_32FC1);
      out->setTo(0.f);
    } else {
      cv::absdiff(current_, previous_, difference_);
      cv::boxFilter(difference_, *out, CV_32F, cv::Size(window_, window_));
    }
    std::swap(previous_, current_);
  }

 private:
  int window_;
  cv::Mat luminance_, current_, previous_, difference_;
};

std::unique_ptr<attend::FeatureMap> Create(const attend::ParamBlock& params,
                                           const attend::FeatureSetup&) {
  TemporalChangeOptions options;
  attend::ReadFields(params, TemporalChangeOptions::Fields(), &options);
  if (options.window % 2 == 0) params.Fail("window", "must be odd");
  return std::make_unique<TemporalChange>(options.window);
}

void Register(attend::FeatureRegistry* registry) {
  registry->Add("temporal_change", "luminance change since the previous frame (example plugin)",
                &Create);
}

}  // namespace

ATTEND_PLUGIN("temporal_change", Register)
