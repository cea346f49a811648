#include "features/dnn_decoders.h"

#include <algorithm>
#include <cmath>

namespace attend {

namespace {

// The grid cells of one stride for an input of `input` pixels (its sides multiples of 32).
int Cells(cv::Size input, int stride) { return (input.width / stride) * (input.height / stride); }

int AllCells(cv::Size input) {
  int cells = 0;
  for (const int stride : kDnnStrides) cells += Cells(input, stride);
  return cells;
}

// The rows of an output as a 2-D float matrix (a 1 x N x K tensor as N x K).
cv::Mat Rows(const cv::Mat& value) {
  if (value.dims == 2) return value;
  const int rows = value.size[value.dims - 2], cols = value.size[value.dims - 1];
  return cv::Mat(rows, cols, CV_32F, const_cast<uchar*>(value.ptr()));
}

// The best class of `scores` (a row's class scores) among `classes` (all when empty).
std::pair<int, float> BestClass(const float* scores, int count, const std::vector<int>& classes) {
  int best = -1;
  float best_score = -1.f;
  const auto consider = [&](int c) {
    if (c < count && scores[c] > best_score) best = c, best_score = scores[c];
  };
  if (classes.empty()) {
    for (int c = 0; c < count; ++c) consider(c);
  } else {
    for (const int c : classes) consider(c);
  }
  return {best, best_score};
}

cv::Rect2f CentreBox(float cx, float cy, float w, float h) {
  return cv::Rect2f(cx - 0.5f * w, cy - 0.5f * h, w, h);
}

void DecodeDarknet(const DnnOutputs& outputs, cv::Size input, const std::vector<int>& classes,
                   float min_score, std::vector<DnnBox>* boxes) {
  for (const cv::Mat& value : outputs.values) {
    const cv::Mat rows = Rows(value);
    for (int r = 0; r < rows.rows; ++r) {
      const float* row = rows.ptr<float>(r);
      const auto [best, score] = BestClass(row + 5, rows.cols - 5, classes);
      if (best < 0 || score < min_score) continue;
      boxes->push_back({CentreBox(row[0] * input.width, row[1] * input.height,
                                  row[2] * input.width, row[3] * input.height),
                        best, score});
    }
  }
}

void DecodeYolox(const DnnOutputs& outputs, cv::Size input, const std::vector<int>& classes,
                 float min_score, std::vector<DnnBox>* boxes) {
  const cv::Mat rows = Rows(outputs.values[0]);
  int r = 0;
  for (const int stride : kDnnStrides) {
    const int columns = input.width / stride, lines = input.height / stride;
    for (int gy = 0; gy < lines; ++gy) {
      for (int gx = 0; gx < columns; ++gx, ++r) {
        const float* row = rows.ptr<float>(r);
        const float objectness = row[4];
        if (objectness < min_score) continue;  // the score is at most the objectness
        const auto [best, class_score] = BestClass(row + 5, rows.cols - 5, classes);
        const float score = objectness * class_score;
        if (best < 0 || score < min_score) continue;
        boxes->push_back({CentreBox((gx + row[0]) * stride, (gy + row[1]) * stride,
                                    std::exp(row[2]) * stride, std::exp(row[3]) * stride),
                          best, score});
      }
    }
  }
}

int IndexOf(const DnnOutputs& outputs, const std::string& name) {
  const auto found = std::find(outputs.names.begin(), outputs.names.end(), name);
  return found == outputs.names.end() ? -1 : static_cast<int>(found - outputs.names.begin());
}

void DecodeYunet(const DnnOutputs& outputs, cv::Size input, float min_score,
                 std::vector<DnnBox>* boxes) {
  for (const int stride : kDnnStrides) {
    const std::string suffix = "_" + std::to_string(stride);
    const cv::Mat cls = Rows(outputs.values[IndexOf(outputs, "cls" + suffix)]);
    const cv::Mat obj = Rows(outputs.values[IndexOf(outputs, "obj" + suffix)]);
    const cv::Mat bbox = Rows(outputs.values[IndexOf(outputs, "bbox" + suffix)]);
    const int columns = input.width / stride, lines = input.height / stride;
    for (int gy = 0, r = 0; gy < lines; ++gy) {
      for (int gx = 0; gx < columns; ++gx, ++r) {
        const float c = std::clamp(cls.at<float>(r, 0), 0.f, 1.f);
        const float o = std::clamp(obj.at<float>(r, 0), 0.f, 1.f);
        const float score = std::sqrt(c * o);
        if (score < min_score) continue;
        const float* b = bbox.ptr<float>(r);
        boxes->push_back({CentreBox((gx + b[0]) * stride, (gy + b[1]) * stride,
                                    std::exp(b[2]) * stride, std::exp(b[3]) * stride),
                          0, score});
      }
    }
  }
}

std::string AllShapes(const DnnOutputs& outputs) {
  std::string text;
  for (size_t i = 0; i < outputs.values.size(); ++i) {
    if (!text.empty()) text += ", ";
    const std::string name = i < outputs.names.size() ? outputs.names[i] : "?";
    text += name + " " + ShapeText(outputs.values[i]);
  }
  return text.empty() ? "no outputs" : text;
}

// Whether `value` is a float 1 x rows x cols (or rows x cols) tensor.
bool IsTable(const cv::Mat& value, int rows, int cols) {
  if (value.depth() != CV_32F) return false;
  if (value.dims == 2) return value.rows == rows && value.cols == cols;
  return value.dims == 3 && value.size[0] == 1 && value.size[1] == rows && value.size[2] == cols;
}

std::string CheckDarknet(const DnnOutputs& outputs, int max_class) {
  for (const cv::Mat& value : outputs.values) {
    if (value.depth() != CV_32F || value.dims != 2 || value.cols < 6 ||
        value.cols < 5 + max_class + 1) {
      return "darknet expects each output as rows of cx cy w h objectness and at least " +
             std::to_string(std::max(1, max_class + 1)) + " class scores";
    }
  }
  return outputs.values.empty() ? "darknet expects at least one [yolo] output" : "";
}

std::string CheckYolox(const DnnOutputs& outputs, cv::Size input, int max_class) {
  const int cells = AllCells(input);
  if (outputs.values.size() == 1) {
    const cv::Mat& value = outputs.values[0];
    const int cols = value.dims >= 2 ? value.size[value.dims - 1] : 0;
    if (cols >= 5 + max_class + 1 && IsTable(value, cells, cols)) return "";
  }
  return "yolox expects one output of 1x" + std::to_string(cells) + "x(5 + classes, at least " +
         std::to_string(6 + std::max(0, max_class)) + ") for a " + std::to_string(input.width) +
         "x" + std::to_string(input.height) + " input";
}

std::string CheckYunet(const DnnOutputs& outputs, cv::Size input) {
  for (const int stride : kDnnStrides) {
    const int cells = Cells(input, stride);
    for (const auto& [head, cols] : {std::pair<const char*, int>{"cls", 1}, {"obj", 1},
                                     {"bbox", 4}}) {
      const std::string name = std::string(head) + "_" + std::to_string(stride);
      const int index = IndexOf(outputs, name);
      if (index < 0 || !IsTable(outputs.values[index], cells, cols)) {
        return "yunet expects outputs cls_S, obj_S (1xCx1) and bbox_S (1xCx4) for the strides "
               "8, 16 and 32, C the stride's cells (" +
               std::to_string(cells) + " for " + name + " at a " + std::to_string(input.width) +
               "x" + std::to_string(input.height) + " input)";
      }
    }
  }
  return "";
}

}  // namespace

std::string ShapeText(const cv::Mat& value) {
  if (value.empty()) return "(empty)";
  std::string text;
  for (int d = 0; d < value.dims; ++d) {
    text += (d == 0 ? "" : "x") + std::to_string(value.size[d]);
  }
  return text;
}

std::string CheckDnnOutputs(DnnDecoder decoder, const DnnOutputs& outputs, cv::Size input,
                            int max_class) {
  std::string expected;
  switch (decoder) {
    case DnnDecoder::kDarknet:
      expected = CheckDarknet(outputs, max_class);
      break;
    case DnnDecoder::kYolox:
      expected = CheckYolox(outputs, input, max_class);
      break;
    case DnnDecoder::kYunet:
      expected = CheckYunet(outputs, input);
      break;
  }
  return expected.empty() ? "" : expected + "; the network gives " + AllShapes(outputs);
}

std::vector<DnnBox> DecodeDnnOutputs(DnnDecoder decoder, const DnnOutputs& outputs,
                                     cv::Size input, const std::vector<int>& classes,
                                     float min_score) {
  std::vector<DnnBox> boxes;
  switch (decoder) {
    case DnnDecoder::kDarknet:
      DecodeDarknet(outputs, input, classes, min_score, &boxes);
      break;
    case DnnDecoder::kYolox:
      DecodeYolox(outputs, input, classes, min_score, &boxes);
      break;
    case DnnDecoder::kYunet:
      DecodeYunet(outputs, input, min_score, &boxes);
      break;
  }
  return boxes;
}

}  // namespace attend
