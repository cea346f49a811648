// Where attend finds its bundled files (configs/, sequences/): $ATTEND_HOME, or the source
// tree it was built from; and the bundled default sequence.
#pragma once

#include <string>

#include "tracker/target_tracker.h"

namespace attend {

// The project folder holding configs/ and sequences/.
std::string AttendHome();

// configs/default.yaml below AttendHome().
std::string DefaultConfigPath();

// configs/segment.yaml below AttendHome(): the defaults of `attend segment`.
std::string SegmentConfigPath();

// The file that `attend track` and Python's attend.Tracker start a tracker of kind `kind` from:
// its row's config_file under configs/ below AttendHome() (configs/track.yaml for the BIP, its
// correlation mode), "" for a kind without one.
std::string TrackConfigPath(TrackerKind kind);

// The bundled default sequence, rendered from sequences/lab.yaml on first use into
// sequences/generated/lab-<hash of the scene file> (a changed scene renders anew). Returns the
// sequence folder. `quiet` silences the one-line notice printed while rendering.
std::string EnsureBundledSequence(bool quiet);

}  // namespace attend
