#include "pipeline/overlay.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
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

cv::Mat DrawOverlay(const cv::Mat& left, const FrameRecord& record) {
  cv::Mat overlay = left.clone();
  const double font_scale = std::max(0.35, left.cols / 900.0);
  for (const TargetRecord& target : record.targets) {
    const cv::Scalar colour = TargetColour(target.id);
    const bool visible = Visible(target.state);
    const int thickness = target.state == TargetState::kNew ? 3 : (visible ? 2 : 1);
    cv::rectangle(overlay, target.bbox, colour, thickness, visible ? cv::LINE_8 : cv::LINE_4);
    // Ids count up in the order objects were attended, so the label is the focus order.
    std::string label = std::to_string(target.id);
    label.insert(0, 1, '#');
    if (target.kind == "skin") label += " skin";
    if (!visible) label.append(" (").append(TargetStateName(target.state)).append(")");
    const cv::Point anchor(target.bbox.x, std::max(10, target.bbox.y - 3));
    cv::putText(overlay, label, anchor, cv::FONT_HERSHEY_SIMPLEX, font_scale, cv::Scalar(0, 0, 0),
                3, cv::LINE_AA);
    cv::putText(overlay, label, anchor, cv::FONT_HERSHEY_SIMPLEX, font_scale, colour, 1,
                cv::LINE_AA);
  }
  const std::string caption = "frame " + std::to_string(record.frame) + "  targets " +
                              std::to_string(record.targets.size());
  const cv::Point corner(4, left.rows - 6);
  cv::putText(overlay, caption, corner, cv::FONT_HERSHEY_SIMPLEX, font_scale, cv::Scalar(0, 0, 0),
              3, cv::LINE_AA);
  cv::putText(overlay, caption, corner, cv::FONT_HERSHEY_SIMPLEX, font_scale,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  return overlay;
}

}  // namespace attend
