#include "semiattentive/motion_grouping.h"

#include <opencv2/imgproc.hpp>
#include <utility>

#include "util/error.h"

namespace attend {

MotionGrouping::MotionGrouping(float min_speed, float flow_tolerance)
    : min_speed_(min_speed), flow_tolerance_(flow_tolerance) {
  constexpr int kDisPresetMedium = 2;  // cv::DISOpticalFlow::PRESET_MEDIUM
  solver_ = cvextra::Get("select.group_min_speed (OpenCV's DIS optical flow)")
                .CreateDisFlow(kDisPresetMedium);
}

void MotionGrouping::NextFrame(const cv::Mat& bgr) {
  std::swap(grey_, previous_grey_);
  cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
  flow_state_ = 0;
}

bool MotionGrouping::RegionFlow(const Segmentation& segmentation) {
  if (flow_state_ != 0) return flow_state_ > 0;
  flow_state_ = -1;
  if (previous_grey_.empty() || previous_grey_.size() != grey_.size()) return false;
  ATTEND_CHECK(solver_ != nullptr) << "motion grouping without its flow";
  solver_->Calc(previous_grey_, grey_, &flow_);
  MeanFlowPerRegion(segmentation.labels, segmentation.regions.size());
  flow_state_ = 1;
  return true;
}

void MotionGrouping::MeanFlowPerRegion(const cv::Mat& labels, size_t regions) {
  // The flow bleeds across the edges of what moves (the solver smooths it), so a region's flow
  // is its mean away from its border, kFlowBorder px in.
  border_.create(labels.size(), CV_8UC1);
  border_.setTo(0);
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const int* below = y + 1 < labels.rows ? labels.ptr<int>(y + 1) : nullptr;
    uchar* edge = border_.ptr<uchar>(y);
    uchar* edge_below = below != nullptr ? border_.ptr<uchar>(y + 1) : nullptr;
    for (int x = 0; x < labels.cols; ++x) {
      if (x + 1 < labels.cols && label[x + 1] != label[x]) edge[x] = edge[x + 1] = 255;
      if (below != nullptr && below[x] != label[x]) edge[x] = edge_below[x] = 255;
    }
  }
  cv::dilate(border_, border_,
             cv::getStructuringElement(cv::MORPH_RECT,
                                       cv::Size(2 * kFlowBorder + 1, 2 * kFlowBorder + 1)));
  std::vector<cv::Point2d> inner_sum(regions), all_sum(regions);
  std::vector<int> inner_count(regions, 0), all_count(regions, 0);
  for (int y = 0; y < flow_.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const uchar* edge = border_.ptr<uchar>(y);
    const cv::Point2f* flow = flow_.ptr<cv::Point2f>(y);
    for (int x = 0; x < flow_.cols; ++x) {
      if (label[x] < 0) continue;
      const cv::Point2d pixel(flow[x].x, flow[x].y);
      all_sum[label[x]] += pixel;
      ++all_count[label[x]];
      if (!edge[x]) inner_sum[label[x]] += pixel, ++inner_count[label[x]];
    }
  }
  region_flow_.assign(regions, cv::Point2f());
  for (size_t r = 0; r < regions; ++r) {
    if (inner_count[r] > 0) {
      region_flow_[r] = cv::Point2f(inner_sum[r] * (1.0 / inner_count[r]));
    } else if (all_count[r] > 0) {
      region_flow_[r] = cv::Point2f(all_sum[r] * (1.0 / all_count[r]));
    }
  }
}

void MotionGrouping::Group(const Segmentation& segmentation, const std::vector<uint8_t>& taken,
                           double max_area, std::vector<int>* members, double* seed_area) {
  if (!RegionFlow(segmentation)) return;
  // The proto-object's motion: its regions' flows weighted by their areas.
  cv::Point2d motion;
  double area = 0.0;
  for (const int region : *members) {
    motion += cv::Point2d(region_flow_[region]) * segmentation.regions[region].area;
    area += segmentation.regions[region].area;
  }
  if (area <= 0.0) return;
  motion *= 1.0 / area;
  const double speed = cv::norm(motion);
  if (speed < min_speed_) return;
  const double tolerance = flow_tolerance_ * speed;
  std::vector<uint8_t> in(segmentation.regions.size(), 0);
  for (const int region : *members) in[region] = 1;
  // Outwards from the proto-object, a region at a time (breadth first).
  const RegionAdjacency& adjacency = segmentation.adjacency;
  for (size_t next = 0; next < members->size(); ++next) {
    const int region = (*members)[next];
    for (const int* at = adjacency.NeighboursBegin(region); at != adjacency.NeighboursEnd(region);
         ++at) {
      const int neighbour = *at;
      if (in[neighbour] || taken[neighbour]) continue;
      const int neighbour_area = segmentation.regions[neighbour].area;
      if (neighbour_area > max_area || *seed_area + neighbour_area > max_area) continue;
      if (cv::norm(cv::Point2d(region_flow_[neighbour]) - motion) > tolerance) continue;
      in[neighbour] = 1;
      members->push_back(neighbour);
      *seed_area += neighbour_area;
    }
  }
}

}  // namespace attend
