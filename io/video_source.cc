#include "io/video_source.h"

#include <cmath>
#include <filesystem>
#include <opencv2/videoio.hpp>  // the CAP_ constants only
#include <string>
#include <utility>
#include <vector>

#include "io/ranged_source.h"
#include "util/error.h"
#include "util/opencv_extra.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

class VideoReader final : public NativeReader {
 public:
  enum class Layout { kMono, kPair, kSideBySide };

  VideoReader(const SourceSpec& source, SequenceInfo* info) {
    if (!source.video.empty()) {
      layout_ = Layout::kMono;
      paths_ = {source.video};
    } else if (!source.side_by_side_video.empty()) {
      layout_ = Layout::kSideBySide;
      paths_ = {source.side_by_side_video};
    } else {
      layout_ = Layout::kPair;
      paths_ = {source.left_video, source.right_video};
    }
    std::vector<int> counts;
    for (size_t i = 0; i < paths_.size(); ++i) {
      captures_.push_back(OpenCapture(paths_[i]));
      const double count = captures_[i]->Get(cv::CAP_PROP_FRAME_COUNT);
      counts.push_back(count > 0 && std::isfinite(count) ? static_cast<int>(count) : -1);
    }
    count_ = counts[0];
    if (layout_ == Layout::kPair) {
      if (counts[0] > 0 && counts[1] > 0 && counts[0] != counts[1]) {
        throw InputError(source.Describe() + ": the left video has " + std::to_string(counts[0]) +
                         " frames but the right video has " + std::to_string(counts[1]));
      }
      if (counts[0] < 0 || counts[1] < 0) count_ = -1;
    }
    info->stereo = layout_ != Layout::kMono;
    info->name = fs::path(paths_[0]).stem().string();
    const double fps = captures_[0]->Get(cv::CAP_PROP_FPS);
    if (fps > 0 && std::isfinite(fps)) info->fps = fps;
  }

  int Count() const override { return count_; }

  bool Read(int index, NativeFrame* frame) override {
    // Frames before `index` are grabbed but not decoded: that is how a stride or a first frame
    // skips through a stream that cannot seek exactly.
    while (position_ < index) {
      if (!Advance(/*decode=*/false, nullptr)) return false;
    }
    std::vector<cv::Mat> images;
    if (!Advance(/*decode=*/true, &images)) return false;
    const int read_index = position_ - 1;
    for (size_t i = 0; i < images.size(); ++i) {
      images[i] = VideoFrameToBgr(images[i], read_index, FramePath(i, read_index));
    }
    frame->left_path = FramePath(0, read_index);
    if (layout_ == Layout::kMono) {
      frame->left = images[0];
      frame->right = cv::Mat();
      frame->right_path.clear();
    } else if (layout_ == Layout::kPair) {
      frame->left = images[0];
      frame->right = images[1];
      frame->right_path = FramePath(1, read_index);
    } else {
      const cv::Mat& both = images[0];
      CheckSideBySideWidth(both, read_index, frame->left_path);
      const int half = both.cols / 2;
      // Copies, so that each view is continuous and independent of the other.
      frame->left = both(cv::Rect(0, 0, half, both.rows)).clone();
      frame->right = both(cv::Rect(half, 0, half, both.rows)).clone();
      frame->right_path = frame->left_path;
    }
    return true;
  }

 private:
  static std::unique_ptr<cvextra::Capture> OpenCapture(const std::string& path) {
    // A missing file is reported before OpenCV tries every backend on it. Paths with '%' are
    // image-sequence patterns ("frames/%06d.png") that only the video backend can resolve.
    std::error_code error;
    if (path.find('%') == std::string::npos && !fs::exists(path, error)) {
      throw InputError("video " + path + ": no such file");
    }
    // OpenCV's videoio is in the optional module (util/opencv_extra.h).
    cvextra::Module& opencv = cvextra::Get("video " + path);
    std::unique_ptr<cvextra::Capture> capture;
    try {
      capture = opencv.OpenCapture(path, cv::CAP_ANY);
    } catch (const cv::Exception& e) {
      throw InputError("video " + path + ": cannot be opened: " + e.what());
    }
    if (capture == nullptr || !capture->IsOpened()) {
      throw InputError("video " + path + ": cannot be opened (not a video OpenCV can decode)");
    }
    return capture;
  }

  std::string FramePath(size_t view, int index) const {
    return paths_[view] + "#" + std::to_string(index);
  }

  // Moves every capture one frame on; false at the end of all of them. A pair whose videos end
  // at different frames is inconsistent input.
  bool Advance(bool decode, std::vector<cv::Mat>* images) {
    std::vector<bool> ok(captures_.size());
    for (size_t i = 0; i < captures_.size(); ++i) {
      if (decode) {
        // A fresh matrix per frame: frames handed out earlier must never share its buffer.
        cv::Mat image;
        ok[i] = captures_[i]->Read(&image) && !image.empty();
        images->push_back(image);
      } else {
        ok[i] = captures_[i]->Grab();
      }
    }
    const int index = position_;
    ++position_;
    if (ok.size() == 2 && ok[0] != ok[1]) {
      const size_t ended = ok[0] ? 1 : 0;
      throw InputError(FrameWhere(index, FramePath(ended, index)) + ": the " +
                       (ended == 0 ? "left" : "right") + " video ends here but the " +
                       (ended == 0 ? "right" : "left") + " video goes on");
    }
    return ok[0];
  }

  Layout layout_ = Layout::kMono;
  std::vector<std::string> paths_;
  std::vector<std::unique_ptr<cvextra::Capture>> captures_;
  int count_ = -1;
  int position_ = 0;  // index of the frame the next read or grab returns
};

}  // namespace

std::unique_ptr<FrameSource> OpenVideoSource(const SequenceOptions& options) {
  SequenceInfo info;
  auto reader = std::make_unique<VideoReader>(options.source, &info);
  return OpenRangedSource(options, std::move(reader), std::move(info));
}

}  // namespace attend
