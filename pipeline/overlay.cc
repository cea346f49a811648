#include "pipeline/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <set>
#include <string>

namespace attend {

cv::Scalar TargetColour(int id) {
  // Golden-angle steps around the hue circle keep neighbouring ids apart.
  const double hue = std::fmod(id * 137.508, 360.0);
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue / 2.0, 220, 255));
  cv::Mat bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b c = bgr.at<cv::Vec3b>(0, 0);
  return cv::Scalar(c[0], c[1], c[2]);
}

double OverlayFontScale(int width) { return std::max(0.35, width / 900.0); }

void DrawLabel(cv::Mat* image, const std::string& text, cv::Point at, const cv::Scalar& colour,
               double font_scale) {
  cv::putText(*image, text, at, cv::FONT_HERSHEY_SIMPLEX, font_scale, cv::Scalar(0, 0, 0), 3,
              cv::LINE_AA);
  cv::putText(*image, text, at, cv::FONT_HERSHEY_SIMPLEX, font_scale, colour, 1, cv::LINE_AA);
}

void DrawCaption(cv::Mat* image, const std::string& text, double font_scale) {
  DrawLabel(image, text, cv::Point(4, image->rows - 6), cv::Scalar(255, 255, 255), font_scale);
}

void DrawTargetLabel(cv::Mat* image, int id, const cv::Rect& box, const std::string& suffix,
                     double font_scale) {
  // Ids count up in the order objects were attended, so the label is the focus order.
  std::string label = "#";
  label += std::to_string(id);
  label += suffix;
  // Kept inside the image where it fits: a box at the right edge with a long label (its depth)
  // moves its label left rather than losing the end of it.
  int baseline = 0;
  const int width =
      cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font_scale, 3, &baseline).width;
  const int x = std::max(0, std::min(box.x, image->cols - width));
  DrawLabel(image, label, cv::Point(x, std::max(10, box.y - 3)), TargetColour(id), font_scale);
}

std::string TargetDepthLabel(const TargetRecord& target) {
  char text[48];
  if (target.has_position && std::isfinite(target.position_m[2])) {
    std::snprintf(text, sizeof(text), " Z %.2f m", target.position_m[2]);
    return text;
  }
  if (std::isfinite(target.disparity_px)) {
    std::snprintf(text, sizeof(text), " d %.1f px", target.disparity_px);
    return text;
  }
  return "";
}

cv::Mat DrawOverlay(const cv::Mat& left, const FrameRecord& record) {
  cv::Mat overlay = left.clone();
  const double font_scale = OverlayFontScale(left.cols);
  // A target that ended in this frame and was resumed in it under its id is recorded twice:
  // its old box is drawn, but only the resumed one is labelled, so the two labels do not
  // cover each other.
  std::set<int> seen_ids;
  for (const TargetRecord& target : record.targets) {
    if (Visible(target.state)) seen_ids.insert(target.id);
  }
  for (const TargetRecord& target : record.targets) {
    const bool visible = Visible(target.state);
    const int thickness =
        target.state == TargetState::kNew || target.state == TargetState::kResumed ? 3
                                                                                    : (visible ? 2 : 1);
    cv::rectangle(overlay, target.bbox, TargetColour(target.id), thickness,
                  visible ? cv::LINE_8 : cv::LINE_4);
    std::string suffix = target.kind == "skin" ? " skin" : "";
    if (!target.label.empty()) suffix.append(" ").append(target.label);
    suffix += TargetDepthLabel(target);
    if (!visible || target.state == TargetState::kResumed) {
      suffix.append(" (").append(TargetStateName(target.state)).append(")");
    }
    if (visible || seen_ids.count(target.id) == 0) {
      DrawTargetLabel(&overlay, target.id, target.bbox, suffix, font_scale);
    }
  }
  DrawCaption(&overlay,
              "frame " + std::to_string(record.frame) + "  targets " +
                  std::to_string(record.targets.size()),
              font_scale);
  return overlay;
}

}  // namespace attend
