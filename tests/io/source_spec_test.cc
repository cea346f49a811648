#include "io/source_spec.h"

#include <gtest/gtest.h>

#include <string>

#include "io/sequence_options.h"

namespace attend {
namespace {

TEST(SourceSpec, KindFollowsTheFieldSet) {
  EXPECT_EQ(SourceSpec().Kind(), SourceKind::kNone);
  EXPECT_TRUE(SourceSpec().empty());
  auto kind = [](auto set) {
    SourceSpec spec;
    set(&spec);
    EXPECT_FALSE(spec.empty());
    EXPECT_EQ(spec.SourceCount(), 1);
    return spec.Kind();
  };
  EXPECT_EQ(kind([](SourceSpec* s) { s->folder = "seq"; }), SourceKind::kFolder);
  EXPECT_EQ(kind([](SourceSpec* s) {
              s->left_video = "a.avi";
              s->right_video = "b.avi";
            }),
            SourceKind::kVideoPair);
  EXPECT_EQ(kind([](SourceSpec* s) { s->side_by_side_video = "s.avi"; }), SourceKind::kSideBySide);
  EXPECT_EQ(kind([](SourceSpec* s) { s->video = "m.avi"; }), SourceKind::kVideo);
  EXPECT_EQ(kind([](SourceSpec* s) { s->images = "img"; }), SourceKind::kImages);
  EXPECT_EQ(kind([](SourceSpec* s) { s->camera = 0; }), SourceKind::kLive);
  EXPECT_EQ(kind([](SourceSpec* s) {
              s->gst = "videotestsrc";
              s->camera_right = 1;
            }),
            SourceKind::kLive);
}

TEST(SourceSpec, DescribesLiveViewsAndTheirLayout) {
  SourceSpec spec;
  spec.camera = 0;
  EXPECT_EQ(spec.Describe(), "camera 0");
  spec.gst_right = "videotestsrc";
  EXPECT_EQ(spec.Describe(), "camera 0 + GStreamer pipeline 'videotestsrc'");
  spec.gst_right.clear();
  spec.live.side_by_side = true;
  EXPECT_EQ(spec.Describe(), "side-by-side camera 0");
  EXPECT_EQ(LeftView(spec).FrameStem(), "/dev/video0");
  EXPECT_EQ(RightView(spec).key, "gst_right");
}

TEST(SourceSpec, PathsAreTheFileAndFolderFields) {
  SourceSpec spec;
  spec.folder = "f";
  spec.left_video = "l";
  spec.right_video = "r";
  spec.side_by_side_video = "s";
  spec.video = "v";
  spec.images = "i";
  spec.calib = "c";
  spec.gst = "videotestsrc";  // a pipeline, not a path
  std::string joined;
  for (std::string* path : spec.Paths()) joined += *path;
  EXPECT_EQ(joined, "flrsvic");
  // The calibration is not a source.
  spec = {};
  spec.calib = "c";
  EXPECT_EQ(spec.SourceCount(), 0);
}

// SequenceOptions::Check reports in the order of the keys: the source's kinds and ranges, then
// the frame range's, then the live keys.
TEST(SourceSpec, SequenceChecksTheSourceFirstAndTheLiveKeysAfterTheRange) {
  SequenceOptions options;
  options.source.folder = "seq";
  options.source.video = "v.avi";
  options.stride = 0;
  EXPECT_NE(options.Check().find("at most one source"), std::string::npos) << options.Check();
  options.source = {};
  options.source.camera = 5000;
  EXPECT_NE(options.Check().find("camera must be"), std::string::npos) << options.Check();
  options.source = {};
  options.source.gst = "videotestsrc";
  options.source.live.queue = 0;
  EXPECT_NE(options.Check().find("stride must be >= 1"), std::string::npos) << options.Check();
  options.stride = 1;
  EXPECT_NE(options.Check().find("live.queue"), std::string::npos) << options.Check();
  EXPECT_EQ(options.source.Check(), options.source.CheckLive());
}

}  // namespace
}  // namespace attend
