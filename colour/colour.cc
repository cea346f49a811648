#include "colour/colour.h"

#include <algorithm>
#include <opencv2/core/hal/hal.hpp>

#include "util/error.h"

namespace attend {

namespace {

constexpr float kSqrt3 = 1.7320508075688772f;

// With x = (R-G)+(R-B) and y = sqrt(3)(G-B), H = atan2(y, x), so cos H = x/r and
// sin H = y/r with r = |(x, y)|: no trigonometry is needed.
inline void Cylinder(float r, float g, float b, float* out) {
  const float sum = r + g + b;
  const float minimum = std::min(r, std::min(g, b));
  const float maximum = std::max(r, std::max(g, b));
  const float x = 2.f * r - g - b;
  const float y = kSqrt3 * (g - b);
  const float length = std::sqrt(x * x + y * y);
  // S = 1 - 3 min / (R + G + B), scaled to [0, 255]; 0 for black and for greys.
  const float s = sum > 0.f ? 255.f * (1.f - 3.f * minimum / sum) : 0.f;
  const float scale = length > 0.f ? s / length : 0.f;
  out[0] = x * scale;
  out[1] = y * scale;
  out[2] = maximum;
}

inline void Tsl(float r, float g, float b, float* out) {
  constexpr float kTwoPi = 6.283185307179586f;
  const float sum = r + g + b;
  float t = 0.f, s = 0.f;
  if (sum > 0.f) {
    const float rp = r / sum - 1.f / 3.f;
    const float gp = g / sum - 1.f / 3.f;
    s = 255.f * std::sqrt(9.f / 5.f * (rp * rp + gp * gp));
    if (gp > 0.f) {
      t = std::atan(rp / gp) / kTwoPi + 0.25f;
    } else if (gp < 0.f) {
      t = std::atan(rp / gp) / kTwoPi + 0.75f;
    }
  }
  out[0] = t;
  out[1] = s;
  out[2] = 0.299f * r + 0.587f * g + 0.114f * b;
}

// Cylinder() over a row of 8-bit BGR pixels, in chunks, written so that the compiler
// vectorises it (it does not vectorise Cylinder()'s branches and square root):
// - the channels are first split into integer arrays (SSE2 cannot shuffle bytes);
// - sums, differences, minimum and maximum of the channels are exact in integers;
// - no division needs a branch: black takes minimum 1 and sum 3, which gives saturation 0,
//   and a grey phasor (x = y = 0) takes length 1, its saturation being 0 already;
// - the square roots go through cv::hal::sqrt32f, since GCC does not vectorise std::sqrt
//   under its default -fmath-errno.
// Every other float operation is Cylinder()'s, on the same values in the same order, so the
// results are the same to the bit.
void CylinderRow(const uchar* bgr, int n, float* out) {
  constexpr int kChunk = 128;
  int32_t blue[kChunk], green[kChunk], red[kChunk];
  float x[kChunk], y[kChunk], s[kChunk], v[kChunk], length[kChunk];
  for (int start = 0; start < n; start += kChunk) {
    const int count = std::min(kChunk, n - start);
    const uchar* in = bgr + 3 * start;
    for (int i = 0; i < count; ++i) {
      blue[i] = in[3 * i];
      green[i] = in[3 * i + 1];
      red[i] = in[3 * i + 2];
    }
    for (int i = 0; i < count; ++i) {
      const int r = red[i], g = green[i], b = blue[i];
      const int sum = r + g + b;
      const int black = sum == 0;
      const int grey = (2 * r - g - b == 0) & (g == b);
      x[i] = static_cast<float>(2 * r - g - b);
      y[i] = kSqrt3 * static_cast<float>(g - b);
      length[i] = x[i] * x[i] + y[i] * y[i] + static_cast<float>(grey);
      const float minimum = static_cast<float>(std::min(r, std::min(g, b)) + black);
      s[i] = 255.f * (1.f - 3.f * minimum / static_cast<float>(sum + 3 * black));
      v[i] = static_cast<float>(std::max(r, std::max(g, b)));
    }
    cv::hal::sqrt32f(length, length, count);
    float* result = out + 3 * start;
    for (int i = 0; i < count; ++i) {
      const float scale = s[i] / length[i];
      result[3 * i] = x[i] * scale;
      result[3 * i + 1] = y[i] * scale;
      result[3 * i + 2] = v[i];
    }
  }
}

template <void (*Convert)(float, float, float, float*)>
void ConvertImage(const cv::Mat& bgr, cv::Mat* out) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << "expected an 8-bit BGR image, got type " << bgr.type();
  out->create(bgr.size(), CV_32FC3);
  for (int row = 0; row < bgr.rows; ++row) {
    const uchar* in = bgr.ptr<uchar>(row);
    float* result = out->ptr<float>(row);
    for (int col = 0; col < bgr.cols; ++col) {
      Convert(in[2], in[1], in[0], result);
      in += 3;
      result += 3;
    }
  }
}

}  // namespace

CylinderColour CylinderFromRgb(float r, float g, float b) {
  float out[3];
  Cylinder(r, g, b, out);
  return {out[0], out[1], out[2]};
}

cv::Vec2f TslChrominance(float r, float g, float b) {
  float out[3];
  Tsl(r, g, b, out);
  return {out[0], out[1]};
}

void BgrToCylinder(const cv::Mat& bgr, cv::Mat* out) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << "expected an 8-bit BGR image, got type " << bgr.type();
  out->create(bgr.size(), CV_32FC3);
  for (int row = 0; row < bgr.rows; ++row) {
    CylinderRow(bgr.ptr<uchar>(row), bgr.cols, out->ptr<float>(row));
  }
}

void BgrToTsl(const cv::Mat& bgr, cv::Mat* out) { ConvertImage<Tsl>(bgr, out); }

cv::Vec3f RgbFromCylinder(const CylinderColour& c) {
  // Invert: V = max, S = 1 - 3 min / sum, and the hue direction (x, y) fixes the differences.
  const float s = Saturation(c) / 255.f;
  if (s <= 0.f) return {c.v, c.v, c.v};
  const float cos_h = c.sx / (255.f * s), sin_h = c.sy / (255.f * s);
  // Unit differences: x = 2R - G - B, y = sqrt(3)(G - B) along (cos H, sin H).
  const float x = cos_h, y = sin_h;
  // Solve R, G, B up to an offset and a scale: R = (2x)/3 + k, G = -x/3 + y/sqrt3 + k,
  // B = -x/3 - y/sqrt3 + k, then fit max = V and min/sum = (1 - s)/3.
  const float dr = 2.f * x / 3.f, dg = -x / 3.f + y / kSqrt3, db = -x / 3.f - y / kSqrt3;
  const float dmax = std::max(dr, std::max(dg, db)), dmin = std::min(dr, std::min(dg, db));
  // With channel = a * d + k: max = a dmax + k = V; min / sum = (a dmin + k) / (3k) since the
  // d's sum to zero, so a dmin + k = k (1 - s), i.e. k = -a dmin / s.
  const float a = c.v / (dmax - dmin / s);
  const float k = -a * dmin / s;
  return {a * dr + k, a * dg + k, a * db + k};
}

}  // namespace attend
