// Sources of image files (docs/SEQUENCES.md): a sequence folder SEQ with SEQ/left/*,
// SEQ/right/* (stereo; monocular without right/) and an optional SEQ/sequence.yaml, and a plain
// folder of frames DIR/* (monocular, for example an OTB sequence's img/).
#pragma once

#include <memory>
#include <string>

#include "io/frame_source.h"
#include "io/sequence_options.h"

namespace attend {

// The sequence folder options.source.folder. InputError when it is missing, has no left/ or no
// frames, when left/ and right/ differ in count or in the names of their frames, or when its
// sequence.yaml is bad.
std::unique_ptr<FrameSource> OpenFolderSource(const SequenceOptions& options);

// Reads SEQ/sequence.yaml into `info` (name, fps, focal_px, baseline_m; the name and fps keep
// info's values when absent). The file describes the data, so any problem in it is bad input:
// InputError with the file and line. `generator` and `frames` are notes for people, never read.
void ReadSequenceYaml(const std::string& path, SequenceInfo* info);

// The plain folder options.source.images. InputError when it is missing or holds no frames.
std::unique_ptr<FrameSource> OpenImageFolderSource(const SequenceOptions& options);

}  // namespace attend
