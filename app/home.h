// Where attend finds its bundled files (configs/, sequences/): $ATTEND_HOME, or the source
// tree it was built from; and the bundled default sequence.
#pragma once

#include <string>

namespace attend {

// The project folder holding configs/ and sequences/.
std::string AttendHome();

// configs/default.yaml below AttendHome().
std::string DefaultConfigPath();

// configs/segment.yaml below AttendHome(): the defaults of `attend segment`.
std::string SegmentConfigPath();

// configs/track.yaml below AttendHome(): the defaults of `attend track`.
std::string TrackConfigPath();

// The bundled default sequence, rendered from sequences/lab.yaml on first use into
// sequences/generated/lab-<hash of the scene file> (a changed scene renders anew). Returns the
// sequence folder. `quiet` silences the one-line notice printed while rendering.
std::string EnsureBundledSequence(bool quiet);

}  // namespace attend
