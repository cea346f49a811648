// The ranges and the colour member that the field tables of a scene share (synth/scene.cc,
// synth/street_scene.cc).
#pragma once

#include <vector>

#include "synth/scene.h"
#include "util/option_fields.h"
#include "util/range.h"

namespace attend::scene_fields {

// Bounds that keep every number finite (YAML accepts .inf) without limiting real scenes.
inline constexpr double kLargest = 1e6;

// A length, depth, period or rate: (0, 1e6].
inline Range Positive() { return Range{0.0, kLargest, true, false}; }
// A position or offset: [-1e6, 1e6].
inline Range Coordinate() { return Range::Closed(-kLargest, kLargest); }
inline bool IsPositive(double value) { return value > 0.0 && value <= kLargest; }
inline bool IsCoordinate(double value) { return value >= -kLargest && value <= kLargest; }

// An RGB colour read as [r, g, b], each in [0, 255].
template <typename Owner, Rgb Owner::*kColour>
NumbersMember<Owner> ColourMember() {
  return {[](const Owner& o) { return std::vector<double>((o.*kColour).begin(), (o.*kColour).end()); },
          [](Owner* o, const std::vector<double>& v) { o->*kColour = {v[0], v[1], v[2]}; }, 3};
}

}  // namespace attend::scene_fields
