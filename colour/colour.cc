#include "colour/colour.h"

#include <algorithm>
#include <opencv2/core/hal/hal.hpp>

#include "util/error.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

constexpr float kSqrt3 = 1.7320508075688772f;

// CylinderRow() is compiled for AVX2 and for SSE2, with the same results (util/vector_clones.h).

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

// atan(z) for any z, written without branches so that the image loop vectorises. Two range
// reductions bring the argument to |u| <= tan(pi/8): atan(z) = pi/2 - atan(1/z) for z > 1, and
// atan(w) = pi/4 + atan((w - 1)/(w + 1)); there the Taylor series to u^17 is within 2e-8.
inline float Atan(float z) {
  constexpr float kPi = 3.14159265358979f;
  constexpr float kTanPiOver8 = 0.414213562373095f;
  const float a = std::fabs(z);
  const bool large = a > 1.f;
  const float w = std::min(a, 1.f / a);
  const bool middle = w > kTanPiOver8;
  const float reduced = (w - 1.f) / (w + 1.f);
  const float u = middle ? reduced : w;
  const float u2 = u * u;
  float series = 1.f / 17.f;
  series = 1.f / 15.f - u2 * series;
  series = 1.f / 13.f - u2 * series;
  series = 1.f / 11.f - u2 * series;
  series = 1.f / 9.f - u2 * series;
  series = 1.f / 7.f - u2 * series;
  series = 1.f / 5.f - u2 * series;
  series = 1.f / 3.f - u2 * series;
  series = 1.f - u2 * series;
  float angle = (middle ? kPi / 4.f : 0.f) + u * series;
  angle = large ? kPi / 2.f - angle : angle;
  return z < 0.f ? -angle : angle;
}

// T = atan(r'/g') / 2 pi + 1/4 (g' > 0) or + 3/4 (g' < 0), 0 when g' = 0; S = sqrt(9/5 (r'^2 +
// g'^2)) scaled to [0, 255]; r' = r/(r+g+b) - 1/3, g' likewise; L = 0.299 R + 0.587 G +
// 0.114 B. Black gives T = S = 0. Every value is computed, then selected: no branches.
inline void Tsl(float r, float g, float b, float* t, float* s, float* l) {
  constexpr float kTwoPi = 6.283185307179586f;
  const float sum = r + g + b;
  const float inverse = 1.f / std::max(sum, 1.f);
  const float rp = r * inverse - 1.f / 3.f;
  const float gp = g * inverse - 1.f / 3.f;
  const float saturation = 255.f * std::sqrt(9.f / 5.f * (rp * rp + gp * gp));
  // gp = 0 makes the quotient infinite or NaN; its T is 0 whatever Atan returns.
  const float tint = Atan(rp / gp) / kTwoPi + (gp > 0.f ? 0.25f : 0.75f);
  // g' = 0 exactly when 3G = R + G + B, which is exact for 8-bit channels; the rounded g' of
  // such a colour may not be exactly 0.
  *t = (sum > 0.f) & (3.f * g != sum) ? tint : 0.f;
  *s = sum > 0.f ? saturation : 0.f;
  *l = 0.299f * r + 0.587f * g + 0.114f * b;
}

// One row of planar R, G, B to planar T, S, L; the arrays do not overlap.
// Not inlined: the caller's pointers into one buffer would hide that the arrays are distinct.
__attribute__((noinline)) void TslRow(const float* __restrict r, const float* __restrict g,
                                      const float* __restrict b, float* __restrict t,
                                      float* __restrict s, float* __restrict l, int count) {
  for (int i = 0; i < count; ++i) Tsl(r[i], g[i], b[i], &t[i], &s[i], &l[i]);
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
ATTEND_VECTOR_CLONES void CylinderRow(const uchar* bgr, int n, float* out) {
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

}  // namespace

CylinderColour CylinderFromRgb(float r, float g, float b) {
  float out[3];
  Cylinder(r, g, b, out);
  return {out[0], out[1], out[2]};
}

cv::Vec2f TslChrominance(float r, float g, float b) {
  float t, s, l;
  Tsl(r, g, b, &t, &s, &l);
  return {t, s};
}

void BgrToCylinder(const cv::Mat& bgr, cv::Mat* out) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << "expected an 8-bit BGR image, got type " << bgr.type();
  out->create(bgr.size(), CV_32FC3);
  for (int row = 0; row < bgr.rows; ++row) {
    CylinderRow(bgr.ptr<uchar>(row), bgr.cols, out->ptr<float>(row));
  }
}

void BgrToTsl(const cv::Mat& bgr, cv::Mat* out) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << "expected an 8-bit BGR image, got type " << bgr.type();
  out->create(bgr.size(), CV_32FC3);
  ForEachTslRow(bgr, [out](int row, const float* t, const float* s, const float* l) {
    float* result = out->ptr<float>(row);
    for (int col = 0; col < out->cols; ++col) {
      result[3 * col] = t[col];
      result[3 * col + 1] = s[col];
      result[3 * col + 2] = l[col];
    }
  });
}

void ForEachTslRow(const cv::Mat& bgr,
                   const std::function<void(int y, const float* t, const float* s,
                                            const float* l)>& row_done) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << "expected an 8-bit BGR image, got type " << bgr.type();
  // Row by row through planar buffers, so that the arithmetic runs on whole vectors.
  const int cols = bgr.cols;
  cv::AutoBuffer<float> buffer(6 * cols);
  float* const r = buffer.data();
  float* const g = r + cols;
  float* const b = g + cols;
  float* const t = b + cols;
  float* const s = t + cols;
  float* const l = s + cols;
  for (int row = 0; row < bgr.rows; ++row) {
    const uchar* in = bgr.ptr<uchar>(row);
    for (int col = 0; col < cols; ++col) {
      b[col] = in[3 * col];
      g[col] = in[3 * col + 1];
      r[col] = in[3 * col + 2];
    }
    TslRow(r, g, b, t, s, l, cols);
    row_done(row, t, s, l);
  }
}

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
