// The overlay a person watches: the left image with each target's box and id in a colour
// that stays the same for that id, and the order in which targets were attended.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/frame_record.h"

namespace attend {

// A colour per target id, far apart for consecutive ids (golden-angle hue steps).
cv::Scalar TargetColour(int id);

// Draws `record` over a copy of `left` (8-bit BGR): each target's box, and above it its id,
// kind, label, state and depth (TargetDepthLabel).
cv::Mat DrawOverlay(const cv::Mat& left, const FrameRecord& record);

// The background of select.background over `left` (8-bit BGR): each pixel's kind (`kinds`,
// CV_8UC1, semiattentive/background.h's BackgroundKind) tints it: ground green, no_depth blue,
// high cyan, border magenta, large yellow; the rest, the candidates' pixels, as they are.
cv::Mat DrawBackground(const cv::Mat& left, const cv::Mat& kinds);

// A target's depth as the overlay shows it after its id: " Z 2.41 m" with a position (metres,
// whatever the image's size), else " d 12.3 px" with a disparity, "" with neither. The
// disparity is the record's as given: attend run draws its overlay at the working size from
// the record before InputFromWorking, so it is in the pixels of the image drawn on (which
// frames.jsonl's disparity_px, in input pixels, is not when the run scales its frames).
std::string TargetDepthLabel(const TargetRecord& target);

// The pieces every overlay is drawn with (DrawOverlay, attend track's overlay):
// the font scale for an image `width` pixels wide,
double OverlayFontScale(int width);
// a label in `colour` with a dark outline, its baseline starting at `at`,
void DrawLabel(cv::Mat* image, const std::string& text, cv::Point at, const cv::Scalar& colour,
               double font_scale);
// the caption in the bottom-left corner (white on a dark outline),
void DrawCaption(cv::Mat* image, const std::string& text, double font_scale);
// and a target's label above its box: "#ID", then `suffix` (moved left, as far as the image's
// left edge, where it would run over the right edge). With `placed`, the labels drawn before,
// it goes where it covers none of them (inside the box's top, below it, or a line higher), and is
// added to them.
void DrawTargetLabel(cv::Mat* image, int id, const cv::Rect& box, const std::string& suffix,
                     double font_scale, std::vector<cv::Rect>* placed = nullptr);

}  // namespace attend
