#include "pipeline/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <set>
#include <string>
#include <vector>

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
                     double font_scale, std::vector<cv::Rect>* placed) {
  // Ids count up in the order objects were attended, so the label is the focus order.
  std::string label = "#";
  label += std::to_string(id);
  label += suffix;
  // Kept inside the image where it fits: a box at the right edge with a long label (its depth)
  // moves its label left rather than losing the end of it.
  int baseline = 0;
  const int width =
      cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font_scale, 3, &baseline).width;
  const int height = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, font_scale, 3, &baseline)
                         .height + baseline;
  const int x = std::max(0, std::min(box.x, image->cols - width));
  // Above the box; where a label drawn before is there, the first free place of: inside the
  // box's top, below the box, a line higher (a label further away would name another box).
  const std::vector<int> baselines = {std::max(10, box.y - 3), box.y + height,
                                      box.y + box.height + height, box.y - 3 - height};
  int y = baselines.front();
  if (placed != nullptr) {
    for (const int candidate : baselines) {
      const cv::Rect area(x, candidate - height + baseline, width, height);
      if (candidate < 10 || candidate > image->rows) continue;
      const bool free = std::none_of(placed->begin(), placed->end(),
                                     [&](const cv::Rect& r) { return (r & area).area() > 0; });
      if (free) {
        y = candidate;
        break;
      }
    }
    placed->push_back(cv::Rect(x, y - height + baseline, width, height));
  }
  DrawLabel(image, label, cv::Point(x, y), TargetColour(id), font_scale);
}

cv::Mat DrawBackground(const cv::Mat& left, const cv::Mat& kinds) {
  // BGR tints by BackgroundKind, index 0 (none) unused.
  static const cv::Vec3b kTints[] = {{0, 0, 0},     {60, 200, 60},  {220, 120, 40},
                                     {220, 220, 40}, {200, 60, 200}, {40, 220, 220}};
  cv::Mat out = left.clone();
  for (int y = 0; y < out.rows; ++y) {
    const uint8_t* kind = kinds.ptr<uint8_t>(y);
    cv::Vec3b* pixel = out.ptr<cv::Vec3b>(y);
    for (int x = 0; x < out.cols; ++x) {
      if (kind[x] == 0 || kind[x] >= std::size(kTints)) continue;
      for (int c = 0; c < 3; ++c) pixel[x][c] = static_cast<uint8_t>((pixel[x][c] + kTints[kind[x]][c]) / 2);
    }
  }
  return out;
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
  std::vector<cv::Rect> placed;  // the labels drawn so far, which the next ones keep clear of
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
      DrawTargetLabel(&overlay, target.id, target.bbox, suffix, font_scale, &placed);
    }
  }
  DrawCaption(&overlay,
              "frame " + std::to_string(record.frame) + "  targets " +
                  std::to_string(record.targets.size()),
              font_scale);
  return overlay;
}

}  // namespace attend
