// Inhibition of return (thesis 5.1.3, SPEC 2.4): what the attention stage already follows is
// taken out of the saliency before it looks for something new.
//   inhibition = the union of the kept targets' masks, each dilated by `margin` (within its
//                box plus the margin); an occluded target's last box while keep_occluded (and
//                the area its tracker searched it in, occluded_search); the object files'
//                fading predicted boxes (semiattentive/object_files.h)
//   inhibited  = saliency * (1 - inhibition)
// `covered` marks the pixels of the active targets themselves (their masks, or their boxes
// while occluded): a colour region that overlaps it belongs to a target already.
#pragma once

#include <opencv2/core.hpp>

#include "semiattentive/object_files.h"
#include "util/option_fields.h"

namespace attend {

struct InhibitionOptions {
  int margin = 3;             // pixels of dilation around each tracked mask
  bool keep_occluded = true;  // occluded targets inhibit their last box
  // ... and the area their tracker searched them in this frame (the box and its ROI border):
  // an object that reappears there is the occluded target coming back, not a new one.
  bool occluded_search = true;
  static const OptionFields<InhibitionOptions>& Fields();
};

// The inhibition of one frame, built target by target; its maps are kept between frames so
// that a frame of the same size allocates nothing.
class Inhibition {
 public:
  explicit Inhibition(const InhibitionOptions& options);

  // A new frame of `size`: nothing inhibited or covered.
  void Reset(cv::Size size);
  // A kept target: its mask `own` (CV_8UC1, frame size) with bounding box `box`, in `image`.
  // `in_front` (depth in the loop; CV_8UC1 of the frame's size, or empty: none): pixels nearer
  // than the target by depth.inhibit_band_px, which it does not inhibit, and `apart`, those
  // nearer or farther by depth.separate_px, which it does not cover.
  void AddTarget(const cv::Mat& own, const cv::Rect& box, const cv::Rect& image,
                 const cv::Mat& in_front = cv::Mat(), const cv::Mat& apart = cv::Mat());
  // An occluded target last at `box` (clipped to `image`), searched in `roi` this frame
  // (empty: not searched); nothing unless keep_occluded.
  void AddOccluded(const cv::Rect& box, const cv::Rect& roi, const cv::Rect& image,
                   const cv::Mat& in_front = cv::Mat(), const cv::Mat& apart = cv::Mat());
  // Adds the object files' inhibition and inhibits `saliency` (CV_32FC1); returns the
  // inhibited pixels.
  int Apply(const cv::Mat& saliency, const ObjectFiles& files);
  // Lets go of the maps of the last frame that someone else still holds (util/shared_mat.h).
  void ReleaseShared();

  const cv::Mat& inhibition() const { return inhibition_; }  // CV_32FC1, 0 or 1
  const cv::Mat& inhibited() const { return inhibited_; }    // CV_32FC1
  const cv::Mat& covered() const { return covered_; }        // CV_8UC1, 255 on a target

 private:
  InhibitionOptions options_;
  cv::Mat kernel_;  // the dilation by `margin`
  cv::Mat inhibition_, inhibited_, covered_;
};

}  // namespace attend
