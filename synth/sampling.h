// The deterministic random numbers both renderers share (docs/SYNTH.md, "Appearance"): the
// mixing of seeds, the value-noise texture, Gaussian sensor noise and the rounding of a shaded
// value to a byte. Every function gives the same bits on every platform, so a scene and seed
// render to the same bytes anywhere.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace attend::synth_sampling {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Domains that keep the random streams of different uses apart.
inline constexpr std::uint64_t kSurfaceDomain = 0x5f3759df2c1b3c6dULL;
inline constexpr std::uint64_t kNoiseDomain = 0x2545f4914f6cdd1dULL;
inline constexpr std::uint64_t kFineOctaveDomain = 0x6a09e667f3bcc909ULL;

// SplitMix64's finaliser: a fixed bijective mixing of 64 bits, identical on every platform.
inline std::uint64_t SplitMix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

inline std::uint64_t Mix(std::uint64_t a, std::uint64_t b) { return SplitMix(a ^ SplitMix(b)); }

// A uniform number in [0, 1) from the top 53 bits.
inline double UnitInterval(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

// The texture's random value at lattice point (i, j), in [-1, 1].
inline double LatticeValue(std::uint64_t key, std::int64_t i, std::int64_t j) {
  const std::uint64_t h = SplitMix(key ^ (static_cast<std::uint64_t>(i) * 0x9e3779b97f4a7c15ULL) ^
                                   (static_cast<std::uint64_t>(j) * 0xd1b54a32d192ed03ULL));
  return 2.0 * UnitInterval(h) - 1.0;
}

// Bilinear interpolation of the random lattice at (u, v), in lattice units.
inline double ValueNoise(std::uint64_t key, double u, double v) {
  const double fu = std::floor(u);
  const double fv = std::floor(v);
  const auto i = static_cast<std::int64_t>(fu);
  const auto j = static_cast<std::int64_t>(fv);
  const double s = u - fu;
  const double t = v - fv;
  const double top = (1 - s) * LatticeValue(key, i, j) + s * LatticeValue(key, i + 1, j);
  const double bottom = (1 - s) * LatticeValue(key, i, j + 1) + s * LatticeValue(key, i + 1, j + 1);
  return (1 - t) * top + t * bottom;
}

// The surface texture in [-1, 1]: the lattice plus a finer octave at a quarter of the spacing
// and half the weight, so surfaces show both blotches and grain.
inline double Texture(std::uint64_t key, double u, double v) {
  return (2.0 * ValueNoise(key, u, v) + ValueNoise(key ^ kFineOctaveDomain, 4 * u, 4 * v)) / 3.0;
}

// Gaussian numbers by the Box-Muller transform over mt19937_64, whose output the standard
// fixes; std::normal_distribution is implementation-defined and would break byte identity.
class GaussianSource {
 public:
  explicit GaussianSource(std::uint64_t seed) : engine_(seed) {}
  double Next() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    // u1 in (0, 1] keeps the logarithm finite.
    const double u1 = static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53;
    const double u2 = UnitInterval(engine_());
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(kTwoPi * u2);
    has_spare_ = true;
    return radius * std::cos(kTwoPi * u2);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

inline std::uint8_t ToByte(double value) {
  const double rounded = std::floor(value + 0.5);
  return static_cast<std::uint8_t>(std::clamp(rounded, 0.0, 255.0));
}

}  // namespace attend::synth_sampling
