// Colour spaces of the thesis, over whole images (SPEC 2.1, thesis appendix A).
//
// HSV cylinder: a colour is the vector (S cos H, S sin H, V), the chromatic phasor and the
// luminosity, with S and V in [0, 255] so that the thesis thresholds (T = 10, 20, 30) apply.
// The cylindrical distance of appendix A is the Euclidean distance between these vectors, and
// the mean of colours is the (area-weighted) mean of the vectors.
//
// TSL (Terrillon and Akamatsu), used by the skin model: T (tint) in [0, 1), S (saturation) and
// L (luma) in [0, 255]. As SPEC 2.1 says, T is 0 where g' = 0; that is the limit only for
// greys: chromatic colours with 3G = R + G + B (g' = 0) would have T = 1/2 (r' > 0) or 0/1
// (r' < 0) as limits (docs/SKIN.md measures what this costs the skin model). g' = 0 is tested
// exactly, as 3G = R + G + B.
#pragma once

#include <functional>

#include <cmath>
#include <opencv2/core.hpp>

namespace attend {

// One colour of the HSV cylinder: (S cos H, S sin H, V).
struct CylinderColour {
  float sx = 0.f;  // S cos H
  float sy = 0.f;  // S sin H
  float v = 0.f;   // V = max(R, G, B)
};

// The cylinder vector of one RGB colour (0..255 each).
CylinderColour CylinderFromRgb(float r, float g, float b);

// Saturation S in [0, 255] of a cylinder colour: the length of its chromatic phasor.
inline float Saturation(const CylinderColour& c) { return std::sqrt(c.sx * c.sx + c.sy * c.sy); }

// The cylindrical distance (appendix A, A.2-A.4).
inline float CylinderDistance(const CylinderColour& a, const CylinderColour& b) {
  const float dx = a.sx - b.sx, dy = a.sy - b.sy, dv = a.v - b.v;
  return std::sqrt(dx * dx + dy * dy + dv * dv);
}

// 8-bit BGR (CV_8UC3) to the cylinder image (CV_32FC3: S cos H, S sin H, V). `out` is
// reallocated only when its size or type differs.
void BgrToCylinder(const cv::Mat& bgr, cv::Mat* out);

// 8-bit BGR (CV_8UC3) to TSL (CV_32FC3: T, S, L), SPEC 2.1. Black pixels (R+G+B = 0) get
// T = S = 0.
void BgrToTsl(const cv::Mat& bgr, cv::Mat* out);
// The TSL of `bgr` a row at a time, without the whole image: row(y, t, s, l) for each row y,
// with its T, S and L planes (the values of BgrToTsl, bit for bit), valid during the call.
void ForEachTslRow(const cv::Mat& bgr,
                   const std::function<void(int y, const float* t, const float* s,
                                            const float* l)>& row);

// The TSL chrominance (T, S) of one RGB colour.
cv::Vec2f TslChrominance(float r, float g, float b);

// The RGB colour (0..255, not clamped) of a cylinder colour: the inverse of CylinderFromRgb
// where it is invertible. Used to paint region means.
cv::Vec3f RgbFromCylinder(const CylinderColour& c);

}  // namespace attend
