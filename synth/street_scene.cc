// The field tables of a street scene's blocks (docs/SYNTH.md, "Street scenes") and the
// interpolation of a ground path.
#include <algorithm>

#include "synth/scene.h"
#include "synth/scene_fields.h"
#include "util/error.h"

namespace attend {

using scene_fields::ColourMember;
using scene_fields::Coordinate;
using scene_fields::kLargest;
using scene_fields::Positive;

const OptionFields<GroundKeyframe>& GroundKeyframe::Fields() {
  using K = GroundKeyframe;
  static const OptionFields<K> fields = {
      {"frame", &K::frame, Range::AtLeast(0), "the frame of the keyframe"},
      {"lateral", &K::lateral, Coordinate(), "the centre's lateral position, m, right positive"},
      {"distance", &K::distance, Coordinate(),
       "its distance along the road from the camera's start, m"}};
  return fields;
}

const OptionFields<StreetGround>& StreetGround::Fields() {
  using G = StreetGround;
  static const OptionFields<G> fields = {
      {"colour", ColourMember<G, &G::colour>(), Range::Closed(0, 255), "road [r, g, b]"},
      {"texture", &G::texture, Range::Closed(0, 255), "texture amplitude, grey levels"},
      {"texture_cell", &G::texture_cell_m, Positive(), "texture lattice spacing, m"},
      {"road_width", &G::road_width_m, Positive(), "width of the road, m"},
      {"verge_colour", ColourMember<G, &G::verge_colour>(), Range::Closed(0, 255),
       "[r, g, b] beside the road"},
      {"lane_width", &G::lane_width_m, Range::Closed(0, kLargest), "m; 0: no markings"},
      {"marking_width", &G::marking_width_m, Positive(), "width of a marking, m"},
      {"dash", &G::dash_m, Positive(), "length of a dash, m"},
      {"gap", &G::gap_m, Range::Closed(0, kLargest), "gap between dashes, m"},
      {"marking_colour", ColourMember<G, &G::marking_colour>(), Range::Closed(0, 255),
       "[r, g, b]"}};
  return fields;
}

const OptionFields<StreetSky>& StreetSky::Fields() {
  using S = StreetSky;
  static const OptionFields<S> fields = {
      {"horizon_colour", ColourMember<S, &S::horizon_colour>(), Range::Closed(0, 255),
       "[r, g, b] at the horizon"},
      {"zenith_colour", ColourMember<S, &S::zenith_colour>(), Range::Closed(0, 255),
       "[r, g, b] high up"},
      {"gradient", &S::gradient_deg, Range{0.0, 90.0, true, false},
       "elevation where the zenith colour is reached, degrees"},
      {"texture", &S::texture, Range::Closed(0, 255), "texture amplitude, grey levels"}};
  return fields;
}

const OptionFields<StreetBackdrop>& StreetBackdrop::Fields() {
  using B = StreetBackdrop;
  static const OptionFields<B> fields = {
      {"distance", &B::distance_m, Range::Closed(0, kLargest),
       "along the road from the camera's start, m; 0: no backdrop"},
      {"min_height", &B::min_height_m, Positive(), "lowest facade, m"},
      {"max_height", &B::max_height_m, Positive(), "highest facade, m"},
      {"facade_width", &B::facade_width_m, Positive(), "width of a facade, m"},
      {"colour", ColourMember<B, &B::colour>(), Range::Closed(0, 255), "[r, g, b]"},
      {"colour_spread", &B::colour_spread, Range::Closed(0, 255),
       "each facade's channels vary by up to this"},
      {"texture", &B::texture, Range::Closed(0, 255), "texture amplitude, grey levels"},
      {"texture_cell", &B::texture_cell_m, Positive(), "texture lattice spacing, m"},
      {"window_contrast", &B::window_contrast, Range::Closed(0, 255),
       "how much darker windows are; 0: none"}};
  return fields;
}

GroundKeyframe InterpolateGroundPath(const std::vector<GroundKeyframe>& path, int frame) {
  ATTEND_CHECK(!path.empty()) << "a ground path needs at least one keyframe";
  GroundKeyframe result = frame <= path.front().frame ? path.front() : path.back();
  if (frame > path.front().frame && frame < path.back().frame) {
    const auto next =
        std::upper_bound(path.begin(), path.end(), frame,
                         [](int f, const GroundKeyframe& key) { return f < key.frame; });
    const GroundKeyframe& b = *next;
    const GroundKeyframe& a = *(next - 1);
    const double s = static_cast<double>(frame - a.frame) / (b.frame - a.frame);
    result.lateral = a.lateral + s * (b.lateral - a.lateral);
    result.distance = a.distance + s * (b.distance - a.distance);
  }
  result.frame = frame;
  return result;
}

}  // namespace attend
