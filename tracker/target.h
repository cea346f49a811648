// A target as the tracker keeps it from frame to frame, the frame it is searched in, and the
// steps both modes take with a target found or not (thesis 4.2.5-4.2.7). Not part of the API.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "tracker/roi_pyramid.h"
#include "tracker/target_appearance.h"
#include "tracker/template_update.h"
#include "tracker/tracker_options.h"

namespace attend {
namespace tracker_internal {

struct Target {
  int id = 0;
  TrackSimilarity similarity = TrackSimilarity::kColour;
  std::vector<TemplateLevel> levels;
  cv::Rect box;
  cv::Point2f centroid;
  int border = 0;    // the ROI's border around `box` for the next frame
  cv::Point motion;  // the last displacement found, pixels (d_f of 4.2.3)
  cv::Rect roi;      // the ROI of the current frame
  cv::Mat mask;      // pixels of the last frame; empty when not found
  // Bounded mode: the box before rounding, so that a size that follows its evidence by a
  // small share a frame can grow (a rounded box would round each small step back).
  cv::Rect2d smooth;
  TargetAppearance appearance;  // bounded mode
};

// A frame as the modes read it: the 8-bit BGR frame, its cylinder image when the caller gave
// one (else empty), and its grey image when the mode matches appearances (else empty).
struct TrackFrame {
  cv::Mat bgr;
  cv::Mat cylinder;
  cv::Mat grey;
};

// A target found (4.2.4-4.2.6): its pixels are its regions in `keep`, its template is updated
// from them (the old one moved by `shift` pixels), its centroid is theirs, its motion `shift`
// and its ROI border epsilon again. Returns its pixel count (0: the centroid stays).
int TakeFound(const Hierarchy& h, const std::vector<uint8_t>& in_target, const cv::Rect& keep,
              cv::Point shift, int pyramid_levels, const TrackerOptions& options,
              cv::Size frame_size, Target* target);

// A target not found (4.2.7): no pixels, its template decays by `alpha`, its ROI border grows
// by a pixel up to `epsilon_max`, and it is taken as still.
void TakeMissed(float alpha, int epsilon_max, Target* target);

}  // namespace tracker_internal
}  // namespace attend
