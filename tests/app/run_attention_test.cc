#include "app/run_attention.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace attend {
namespace {

using Arguments = std::vector<std::string>;

TEST(RunSourceArguments, GiveEachSourceInTheRunCommandsFlags) {
  EXPECT_EQ(RunSourceArguments(SourceSpec()), Arguments());
  SourceSpec folder;
  folder.folder = "/data/seq";
  EXPECT_EQ(RunSourceArguments(folder), (Arguments{"--sequence", "/data/seq"}));
  SourceSpec pair;
  pair.left_video = "l.avi";
  pair.right_video = "r.avi";
  EXPECT_EQ(RunSourceArguments(pair), (Arguments{"--left", "l.avi", "--right", "r.avi"}));
  SourceSpec side_by_side;
  side_by_side.side_by_side_video = "s.avi";
  EXPECT_EQ(RunSourceArguments(side_by_side), (Arguments{"--side-by-side", "s.avi"}));
  SourceSpec images;
  images.images = "img";
  EXPECT_EQ(RunSourceArguments(images), (Arguments{"--images", "img"}));
  SourceSpec live;
  live.camera = 0;
  live.gst_right = "videotestsrc";
  live.live.queue = 8;  // read settings have no flag
  EXPECT_EQ(RunSourceArguments(live), (Arguments{"--camera", "0", "--gst-right", "videotestsrc"}));
  live.gst_right.clear();
  live.live.side_by_side = true;
  EXPECT_EQ(RunSourceArguments(live), (Arguments{"--camera", "0", "--side-by-side-live"}));
}

}  // namespace
}  // namespace attend
