// The output layouts of the detector networks the `dnn` backend runs (features/dnn_detector.h),
// decoded into boxes. Each decoder reads the outputs of one forward pass on an input of
// `input` pixels (the network's input, after padding) and returns the boxes in those pixels,
// with their class index and score; nothing here runs a network, so the tests give the
// decoders tensors whose boxes are known.
//
//   darknet  cv::dnn's own decoding of Darknet's [yolo] layers: one output a layer, each row
//            `cx cy w h objectness score_0 score_1 ...`, the box relative to the input and each
//            class score already the objectness times the class probability.
//   yolox    YOLOX's raw head (Ge et al. 2021): one output of 1 x N x (5 + classes), N the
//            cells of the grids of strides 8, 16 and 32 in that order, each row-major; a row
//            is `dx dy log_w log_h objectness class_0 ...` with the box centre at
//            (grid_x + dx, grid_y + dy) x stride, its size exp(log_w, log_h) x stride and the
//            score objectness x class score.
//   yunet    YuNet's raw heads (the face detector of libfacedetection): per stride 8, 16 and 32
//            the outputs cls_S (1 x cells x 1), obj_S (1 x cells x 1) and bbox_S (1 x cells x
//            4), the score sqrt(cls x obj) (each clamped to [0, 1]) and the box as yolox's.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

enum class DnnDecoder { kDarknet, kYolox, kYunet };

// A box the network found, in the pixels of its input.
struct DnnBox {
  cv::Rect2f box;
  int class_index = 0;
  float score = 0.f;
};

// Which outputs of one forward pass a decoder reads: their names (cv::dnn's unconnected output
// layers, in the network's order) and values.
struct DnnOutputs {
  std::vector<std::string> names;
  std::vector<cv::Mat> values;
};

// The strides of the YOLOX and YuNet grids.
inline constexpr int kDnnStrides[] = {8, 16, 32};

// "" when `outputs` fit `decoder` for an input of `input` pixels and classes up to
// `max_class` (the largest class index asked for); otherwise what was expected and the shapes
// found, for an error message.
std::string CheckDnnOutputs(DnnDecoder decoder, const DnnOutputs& outputs, cv::Size input,
                            int max_class);

// The boxes of `outputs` (which CheckDnnOutputs accepted) whose class is in `classes` (any class
// when empty; yunet has one) and whose score is at least `min_score`, each row giving at most
// one box: its best class among `classes`.
std::vector<DnnBox> DecodeDnnOutputs(DnnDecoder decoder, const DnnOutputs& outputs,
                                     cv::Size input, const std::vector<int>& classes,
                                     float min_score);

// "1x3549x85" for an error message.
std::string ShapeText(const cv::Mat& value);

}  // namespace attend
