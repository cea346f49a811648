#include "io/sequence.h"

#include <optional>
#include <string>

#include "io/folder_source.h"
#include "io/kitti_source.h"
#include "io/live_source.h"
#include "io/video_source.h"
#include "util/error.h"

namespace attend {

std::unique_ptr<FrameSource> OpenFrameSource(const SequenceOptions& options) {
  if (options.source.SourceCount() == 0) {
    throw ConfigError(
        "no sequence source is set (folder, left_video + right_video, "
        "side_by_side_video, video, images, camera or gst)");
  }
  const std::string problem = options.Check();
  if (!problem.empty()) throw ConfigError("sequence options: " + problem);
  switch (options.source.Kind()) {
    case SourceKind::kFolder: {
      // KITTI's layouts are given as folders too (SPEC 3.1): a raw drive, a tracking sequence.
      const std::optional<KittiSequence> kitti = FindKittiSequence(options.source.folder);
      return kitti ? OpenKittiSource(options, *kitti) : OpenFolderSource(options);
    }
    case SourceKind::kImages:
      return OpenImageFolderSource(options);
    case SourceKind::kVideoPair:
    case SourceKind::kSideBySide:
    case SourceKind::kVideo:
      return OpenVideoSource(options);
    case SourceKind::kLive:
      return OpenLiveSource(options);
    case SourceKind::kNone:
      break;
  }
  ATTEND_CHECK(false) << "a checked source has a kind";
  return nullptr;
}

}  // namespace attend
