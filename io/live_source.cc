#include "io/live_source.h"

#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <deque>
#include <filesystem>
#include <mutex>
#include <optional>
#include <opencv2/videoio.hpp>
#include <regex>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

#include "io/native_frame.h"
#include "io/sequence_calibration.h"
#include "io/working_size.h"
#include "util/error.h"
#include "util/opencv_extra.h"

namespace attend {

namespace {

using Clock = std::chrono::steady_clock;

std::string Seconds(double seconds) {
  std::ostringstream out;
  out << seconds << " s";
  return out.str();
}

// Opens one view. Every failure is bad input naming the view, and comes within about a second:
// a missing device is refused before OpenCV is asked, and a pipeline that does not parse fails
// in gst_parse_launch.
void OpenView(const LiveView& view, std::unique_ptr<cvextra::Capture>* capture) {
  const std::string what = view.Describe();
  cvextra::Module& opencv = cvextra::Get(what);
  bool opened = false;
  if (view.camera >= 0) {
    const std::string device = view.FrameStem();
    std::error_code error;
    if (!std::filesystem::exists(device, error)) {
      throw InputError(what + ": no such device " + device + " (no V4L2 camera there)");
    }
    try {
      *capture = opencv.OpenCamera(view.camera, cv::CAP_V4L2);
      opened = (*capture)->IsOpened();
    } catch (const cv::Exception& e) {
      throw InputError(what + " (" + device + "): cannot be opened: " + e.what());
    }
    if (!opened) {
      throw InputError(what + " (" + device +
                       "): cannot be opened (not a V4L2 capture device, busy, or not "
                       "readable by this user)");
    }
    return;
  }
  if (!opencv.HasBackend(cv::CAP_GSTREAMER)) {
    throw InputError(what + ": this OpenCV has no GStreamer backend (or it is turned off by "
                            "OPENCV_VIDEOIO_PRIORITY_GSTREAMER=0)");
  }
  try {
    *capture = opencv.OpenCapture(GstPipelineWithSink(view.gst), cv::CAP_GSTREAMER);
    opened = (*capture)->IsOpened();
  } catch (const cv::Exception& e) {
    throw InputError(what + ": cannot be opened: " + e.what());
  }
  if (!opened) {
    throw InputError(what +
                     ": cannot be opened: it does not parse, names an element that is not "
                     "installed, or cannot start (gst-launch-1.0 with the same pipeline says "
                     "why)");
  }
}

// A frame as the capture thread read it: each view at its native size, as the source gave it.
struct CapturedFrame {
  int index = 0;
  std::vector<cv::Mat> views;
  Clock::time_point time;
};

// What the capture thread and the source share. The captures and the settings are fixed before
// the thread starts; the rest is guarded by `mutex`. Shared ownership lets a thread that is
// still blocked in a read when the source goes away finish on its own.
struct CaptureState {
  std::vector<std::unique_ptr<cvextra::Capture>> captures;
  std::vector<LiveView> views;
  int first_frame = 0;
  int last_frame = -1;
  int stride = 1;
  size_t capacity = 2;
  double duration_s = 0.0;

  std::mutex mutex;
  std::condition_variable changed;
  std::deque<CapturedFrame> queue;
  bool opened = false;    // every view is open
  double fps = 0.0;       // the left view's frame rate, when it tells one
  bool stop = false;      // the source asks the thread to end
  bool finished = false;  // the thread has ended
  int captured = 0;
  int dropped = 0;
  LiveEnd end = LiveEnd::kRunning;
  std::string why;
};

// Records how the capture ended, unless an earlier reason was recorded (a timeout seen by the
// source before the thread noticed the stop).
void SetEnd(CaptureState* state, LiveEnd end, const std::string& why) {
  if (state->end != LiveEnd::kRunning) return;
  state->end = end;
  state->why = why;
}

// Opens the views, on the capture thread. When one cannot be opened the capture ends with its
// error (kError) and false.
bool OpenViews(CaptureState* state) {
  try {
    for (size_t i = 0; i < state->views.size(); ++i) {
      OpenView(state->views[i], &state->captures[i]);
    }
    const double fps = state->captures[0]->Get(cv::CAP_PROP_FPS);
    const std::lock_guard<std::mutex> lock(state->mutex);
    state->opened = true;
    if (fps > 0 && std::isfinite(fps)) state->fps = fps;
    return true;
  } catch (const std::exception& e) {
    state->captures.clear();
    const std::lock_guard<std::mutex> lock(state->mutex);
    SetEnd(state, LiveEnd::kError, e.what());
    state->finished = true;
    state->changed.notify_all();
    return false;
  }
}

// Reads frame `index` from every view and, when it is one of the range, queues it (dropping
// the oldest queued frame from a full queue); `first_time` is set by the first frame queued.
// Returns the view whose stream ended, or the number of views when every view delivered.
size_t CaptureFrame(CaptureState* state, int index, std::optional<Clock::time_point>* first_time) {
  const size_t views = state->captures.size();
  // Every view is grabbed before any is decoded, so that the two views of a pair are taken
  // as close together in time as the sources allow.
  for (size_t i = 0; i < views; ++i) {
    if (!state->captures[i]->Grab()) return i;
  }
  const Clock::time_point time = Clock::now();
  if (index < state->first_frame || (index - state->first_frame) % state->stride != 0) {
    return views;
  }
  CapturedFrame frame;
  frame.index = index;
  frame.time = time;
  for (size_t i = 0; i < views; ++i) {
    cv::Mat image;
    if (!state->captures[i]->Retrieve(&image) || image.empty()) return i;
    // A buffer of its own: a backend that kept a reference to the one it decoded into (or
    // lent its own memory) may write the next frame there.
    const bool own = image.u != nullptr && image.u->refcount == 1;
    frame.views.push_back(own ? image : image.clone());
  }
  if (!first_time->has_value()) *first_time = time;
  const std::lock_guard<std::mutex> lock(state->mutex);
  if (state->queue.size() >= state->capacity) {
    state->queue.pop_front();
    ++state->dropped;
  }
  state->queue.push_back(std::move(frame));
  ++state->captured;
  state->changed.notify_all();
  return views;
}

// The capture thread: opens the views, then reads frames as they come and queues those of the
// range, dropping the oldest queued frame when the queue is full. Opening is done here, not by
// the source, because OpenCV's GStreamer backend waits without a timeout for a pipeline to
// start, and one that parsed only in part never does: the source gives up after
// live.timeout_s instead of hanging.
void Capture(const std::shared_ptr<CaptureState>& state) {
  if (!OpenViews(state.get())) return;
  const size_t views = state->views.size();
  const std::string what = views == 2 ? state->views[0].Describe() + " + " +
                                            state->views[1].Describe()
                                      : state->views[0].Describe();
  LiveEnd end = LiveEnd::kRunning;
  std::string why;
  std::optional<Clock::time_point> first_time;
  try {
    for (int index = 0;; ++index) {
      {
        const std::lock_guard<std::mutex> lock(state->mutex);
        if (state->stop) {
          end = LiveEnd::kStopped;
          why = "the run stopped taking frames from " + what;
          break;
        }
      }
      if (state->duration_s > 0 && first_time.has_value() &&
          std::chrono::duration<double>(Clock::now() - *first_time).count() >= state->duration_s) {
        end = LiveEnd::kDuration;
        why = what + ": live.duration_s " + Seconds(state->duration_s) + " passed";
        break;
      }
      const size_t ended = CaptureFrame(state.get(), index, &first_time);
      if (ended != views) {
        end = LiveEnd::kEndOfStream;
        why = state->views[ended].Describe() + ": end of stream after " + std::to_string(index) +
              " frames";
        break;
      }
      if (state->last_frame >= 0 && index >= state->last_frame) {
        end = LiveEnd::kFrameRange;
        why = what + ": the frame range ends at frame " + std::to_string(state->last_frame);
        break;
      }
    }
  } catch (const std::exception& e) {
    end = LiveEnd::kError;
    why = what + ": reading failed: " + e.what();
  }
  // Released here, by the thread that read them, also when the source has let go of it.
  state->captures.clear();
  const std::lock_guard<std::mutex> lock(state->mutex);
  SetEnd(state.get(), end, why);
  state->finished = true;
  state->changed.notify_all();
}

class LiveSource final : public FrameSource {
 public:
  explicit LiveSource(const SequenceOptions& options)
      : options_(options), state_(std::make_shared<CaptureState>()) {
    const LiveView left = LeftView(options.source);
    const LiveView right = RightView(options.source);
    state_->views = {left};
    if (!right.empty()) state_->views.push_back(right);
    state_->captures.resize(state_->views.size());
    state_->first_frame = options.first_frame;
    state_->last_frame = options.last_frame;
    state_->stride = options.stride;
    state_->capacity = static_cast<size_t>(options.source.live.queue);
    state_->duration_s = options.source.live.duration_s;

    info_.stereo = LiveIsStereo(options.source);
    info_.name = right.empty() ? left.Name() : left.Name() + "-" + right.Name();
    info_.frame_count = -1;  // drops make the count unknown ahead
    what_ = options.source.Describe();
    thread_ = std::thread(Capture, state_);

    // The views open and the first frame comes within the timeout, or the source is bad input.
    // The first frame fixes the native size; it stays queued for the first Next().
    std::unique_lock<std::mutex> lock(state_->mutex);
    const bool arrived = state_->changed.wait_for(
        lock, Timeout(), [&] { return !state_->queue.empty() || state_->finished; });
    if (state_->queue.empty()) {
      const std::string timeout = Seconds(options.source.live.timeout_s) + " (live.timeout_s)";
      std::string why;
      if (!arrived && !state_->opened) {
        why = what_ + ": did not start within " + timeout +
              "; a pipeline that names an element that is not there, or that cannot reach its "
              "playing state, never does (gst-launch-1.0 with the same pipeline says why)";
      } else if (!arrived) {
        why = what_ + ": no frame within " + timeout;
      } else if (state_->end == LiveEnd::kError) {
        why = state_->why;
      } else {
        why = what_ + ": the stream ended before its first frame" +
              (options.first_frame > 0
                   ? " of the range (frame " + std::to_string(options.first_frame) + ")"
                   : std::string());
      }
      // A thread still opening a pipeline that never starts is blocked in OpenCV for good:
      // it is left to itself at once rather than given the second a stalled read gets.
      const bool opening = !state_->opened && !state_->finished;
      lock.unlock();
      StopCapture(opening ? std::chrono::milliseconds(0) : std::chrono::seconds(1));
      throw InputError(why);
    }
    if (state_->fps > 0) info_.fps = state_->fps;
    const CapturedFrame& first = state_->queue.front();
    cv::Size native = first.views[0].size();
    if (options.source.live.side_by_side) native.width /= 2;
    lock.unlock();
    SizeSequence(options, native, &info_);
    rectifier_ = AttachCalibration(options, &info_);
  }

  ~LiveSource() override { StopCapture(); }

  const SequenceInfo& info() const override { return info_; }

  void WatchStop(const std::atomic<bool>* stop) override { stop_ = stop; }

  bool Next(StereoFrame* frame) override {
    ATTEND_CHECK(frame != nullptr) << "Next needs a frame to fill";
    if (done_) return false;
    CapturedFrame captured;
    const Clock::time_point deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(Timeout());
    {
      std::unique_lock<std::mutex> lock(state_->mutex);
      while (state_->queue.empty() && !state_->finished) {
        if (stop_ != nullptr && stop_->load()) {
          done_ = true;
          SetEnd(state_.get(), LiveEnd::kStopped,
                 "the run stopped taking frames from " + what_ + " (stop requested)");
          lock.unlock();
          StopCapture();
          return false;
        }
        const Clock::time_point now = Clock::now();
        if (now >= deadline) {
          done_ = true;
          SetEnd(state_.get(), LiveEnd::kTimeout,
                 what_ + " delivered no frame for " + Seconds(options_.source.live.timeout_s) +
                     " (live.timeout_s): it has stopped");
          lock.unlock();
          StopCapture();
          return false;
        }
        // Short waits, so that a stop request is seen soon.
        state_->changed.wait_until(lock, std::min(deadline, now + std::chrono::milliseconds(50)));
      }
      if (state_->queue.empty()) {
        done_ = true;
        if (state_->end == LiveEnd::kError) throw InputError(state_->why);
        return false;
      }
      captured = std::move(state_->queue.front());
      state_->queue.pop_front();
    }
    Fill(std::move(captured), frame);
    return true;
  }

  std::optional<LiveStatus> live_status() const override {
    LiveStatus status;
    status.source = what_;
    status.queue = options_.source.live.queue;
    const std::lock_guard<std::mutex> lock(state_->mutex);
    status.captured = state_->captured;
    status.dropped = state_->dropped;
    status.unprocessed = static_cast<int>(state_->queue.size());
    status.end = state_->end;
    status.why = state_->why;
    if (status.end == LiveEnd::kRunning) {
      // Asked while the source still delivers: the run has stopped taking frames.
      status.end = LiveEnd::kStopped;
      status.why = "the run stopped taking frames from " + what_;
    }
    return status;
  }

 private:
  std::chrono::duration<double> Timeout() const {
    return std::chrono::duration<double>(options_.source.live.timeout_s);
  }

  // Stops the capture thread and joins it. A thread blocked in a read of a stalled source
  // (OpenCV's GStreamer backend waits for the next buffer without a timeout) is given `grace`,
  // a second unless told, then left to end by itself when the read returns: it owns what it
  // uses.
  void StopCapture(std::chrono::milliseconds grace = std::chrono::seconds(1)) {
    if (!thread_.joinable()) return;
    std::unique_lock<std::mutex> lock(state_->mutex);
    state_->stop = true;
    state_->changed.notify_all();
    const bool finished =
        state_->changed.wait_for(lock, grace, [&] { return state_->finished; });
    lock.unlock();
    if (finished) {
      thread_.join();
    } else {
      thread_.detach();
    }
  }

  // The frame at the working size, checked as a file's frames are.
  void Fill(CapturedFrame captured, StereoFrame* frame) const {
    const int index = captured.index;
    std::vector<std::string> paths;
    for (const LiveView& view : state_->views) {
      paths.push_back(view.FrameStem() + "#" + std::to_string(index));
    }
    cv::Mat left = VideoFrameToBgr(captured.views[0], index, paths[0]);
    cv::Mat right;
    if (options_.source.live.side_by_side) {
      CheckSideBySideWidth(left, index, paths[0]);
      const int half = left.cols / 2;
      right = left(cv::Rect(half, 0, half, left.rows));
      left = left(cv::Rect(0, 0, half, left.rows));
      paths.push_back(paths[0]);
    } else if (captured.views.size() == 2) {
      right = VideoFrameToBgr(captured.views[1], index, paths[1]);
    }
    CheckFrameSizes(index, left, paths[0], right, right.empty() ? std::string() : paths[1],
                    info_.native_size);
    if (rectifier_ != nullptr && !right.empty()) {
      // Rectified at the native size, into new buffers (a side-by-side half stays untouched).
      rectifier_->Apply(&left, &right);
    }
    frame->index = index;
    // ToWorkingSize copies a view that is not continuous (a half of a side-by-side frame).
    frame->left = ToWorkingSize(left, info_.size);
    frame->right = right.empty() ? cv::Mat() : ToWorkingSize(right, info_.size);
    frame->left_path = paths[0];
    frame->right_path = right.empty() ? std::string() : paths[1];
    frame->captured = captured.time;
  }

  SequenceOptions options_;
  std::shared_ptr<CaptureState> state_;
  std::thread thread_;
  SequenceInfo info_;
  std::string what_;
  const std::atomic<bool>* stop_ = nullptr;
  bool done_ = false;
  std::shared_ptr<const Rectifier> rectifier_;  // a full calibration's; null otherwise
};

}  // namespace

std::string GstPipelineWithSink(const std::string& pipeline) {
  static const std::regex appsink("(^|[^A-Za-z0-9_-])appsink([^A-Za-z0-9_-]|$)");
  if (std::regex_search(pipeline, appsink)) return pipeline;
  std::string trimmed = pipeline;
  while (!trimmed.empty() && (std::isspace(static_cast<unsigned char>(trimmed.back())) ||
                              trimmed.back() == '!')) {
    trimmed.pop_back();
  }
  return trimmed + " ! videoconvert ! appsink";
}

std::unique_ptr<FrameSource> OpenLiveSource(const SequenceOptions& options) {
  return std::make_unique<LiveSource>(options);
}

}  // namespace attend
