#include "tracker/hog_features.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "util/error.h"

namespace attend {
namespace tracker_internal {

namespace {

constexpr int kSigned = 18;
constexpr int kUnsigned = 9;
constexpr float kTruncate = 0.2f;
constexpr float kTextureScale = 0.2357f;
constexpr float kEnergyFloor = 1e-4f;
// Central differences of 8-bit levels to gradients of levels in [0, 1].
constexpr float kGradientScale = 0.5f / 255.f;

// The signed bin of every gradient (dx, dy) of 8-bit central differences, dx and dy in
// [-255, 255]: the bin whose direction (o x 20 degrees) is nearest the gradient's.
class BinTable {
 public:
  BinTable() : bins_(kSpan * kSpan) {
    for (int dy = -255; dy <= 255; ++dy) {
      for (int dx = -255; dx <= 255; ++dx) {
        const float degrees = cv::fastAtan2(static_cast<float>(dy), static_cast<float>(dx));
        bins_[Index(dx, dy)] =
            static_cast<uchar>(static_cast<int>(degrees * (kSigned / 360.f) + 0.5f) % kSigned);
      }
    }
  }
  int Bin(int dx, int dy) const { return bins_[Index(dx, dy)]; }

 private:
  static constexpr int kSpan = 511;
  static int Index(int dx, int dy) { return (dy + 255) * kSpan + dx + 255; }
  std::vector<uchar> bins_;
};

}  // namespace

void HogCells::Histograms(const cv::Mat& patch, int cell, int rows, int cols) {
  static const BinTable table;
  histogram_.assign(static_cast<size_t>(rows) * cols * kSigned, 0.f);
  grey_.assign(static_cast<size_t>(rows) * cols, 0.f);
  const int height = patch.rows, width = patch.cols;
  for (int r = 0; r < height; ++r) {
    const uchar* up = patch.ptr<uchar>(std::max(r - 1, 0));
    const uchar* row = patch.ptr<uchar>(r);
    const uchar* down = patch.ptr<uchar>(std::min(r + 1, height - 1));
    float* bins_row = histogram_.data() + static_cast<size_t>(r / cell) * cols * kSigned;
    float* grey_row = grey_.data() + static_cast<size_t>(r / cell) * cols;
    for (int c = 0; c < width; ++c) {
      const int left = 3 * std::max(c - 1, 0), right = 3 * std::min(c + 1, width - 1);
      int best_dx = 0, best_dy = 0, best = -1;
      for (int k = 0; k < 3; ++k) {
        const int dx = row[right + k] - row[left + k];
        const int dy = down[3 * c + k] - up[3 * c + k];
        const int m = dx * dx + dy * dy;
        if (m > best) {
          best = m;
          best_dx = dx;
          best_dy = dy;
        }
      }
      grey_row[c / cell] += row[3 * c] + row[3 * c + 1] + row[3 * c + 2];
      if (best <= 0) continue;
      const int bin = table.Bin(best_dx, best_dy);
      bins_row[(c / cell) * kSigned + bin] += std::sqrt(static_cast<float>(best)) * kGradientScale;
    }
  }
}

void HogCells::Compute(const cv::Mat& patch, int cell, std::vector<cv::Mat>* channels) {
  ATTEND_CHECK(cell > 0 && patch.rows % cell == 0 && patch.cols % cell == 0 &&
               patch.type() == CV_8UC3)
      << "HogCells needs an 8-bit BGR patch whose sides are multiples of the cell";
  const int rows = patch.rows / cell, cols = patch.cols / cell;
  Histograms(patch, cell, rows, cols);

  // Energy of each cell's unsigned histogram, padded by one cell (repeated) each side.
  const int padded_cols = cols + 2;
  energy_.assign(static_cast<size_t>(rows + 2) * padded_cols, 0.f);
  for (int r = 0; r < rows + 2; ++r) {
    for (int c = 0; c < cols + 2; ++c) {
      const int rr = std::clamp(r - 1, 0, rows - 1), cc = std::clamp(c - 1, 0, cols - 1);
      const float* bins = histogram_.data() + (static_cast<size_t>(rr) * cols + cc) * kSigned;
      float sum = 0.f;
      for (int o = 0; o < kUnsigned; ++o) {
        const float v = bins[o] + bins[o + kUnsigned];
        sum += v * v;
      }
      energy_[static_cast<size_t>(r) * padded_cols + c] = sum;
    }
  }

  channels->resize(kHogChannels);
  std::array<float*, kHogChannels> out;
  for (int k = 0; k < kHogChannels; ++k) (*channels)[k].create(rows, cols, CV_32F);
  const float grey_scale = 1.f / (3.f * 255.f * cell * cell);
  for (int r = 0; r < rows; ++r) {
    for (int k = 0; k < kHogChannels; ++k) out[k] = (*channels)[k].ptr<float>(r);
    for (int c = 0; c < cols; ++c) {
      // The four 2 x 2 blocks holding cell (r, c); cell (r, c) is (r + 1, c + 1) padded.
      std::array<float, 4> norms;
      int n = 0;
      for (const int br : {0, 1}) {
        for (const int bc : {0, 1}) {
          const float* top = energy_.data() + static_cast<size_t>(r + br) * padded_cols + c + bc;
          const float block = top[0] + top[1] + top[padded_cols] + top[padded_cols + 1];
          norms[n++] = 1.f / std::sqrt(block + kEnergyFloor);
        }
      }
      const float* bins = histogram_.data() + (static_cast<size_t>(r) * cols + c) * kSigned;
      std::array<float, 4> texture = {0.f, 0.f, 0.f, 0.f};
      for (int o = 0; o < kSigned; ++o) {
        float sum = 0.f;
        for (int k = 0; k < 4; ++k) sum += std::min(bins[o] * norms[k], kTruncate);
        out[o][c] = 0.5f * sum;
      }
      for (int o = 0; o < kUnsigned; ++o) {
        const float v = bins[o] + bins[o + kUnsigned];
        float sum = 0.f;
        for (int k = 0; k < 4; ++k) {
          const float t = std::min(v * norms[k], kTruncate);
          sum += t;
          texture[k] += t;
        }
        out[kSigned + o][c] = 0.5f * sum;
      }
      for (int k = 0; k < 4; ++k) out[kSigned + kUnsigned + k][c] = kTextureScale * texture[k];
      out[kHogChannels - 1][c] = grey_[static_cast<size_t>(r) * cols + c] * grey_scale - 0.5f;
    }
  }
}

}  // namespace tracker_internal
}  // namespace attend
