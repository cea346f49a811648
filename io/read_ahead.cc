#include "io/read_ahead.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "util/error.h"

namespace attend {

namespace {

// ReadAhead's source: a worker thread runs the wrapped source's Next() for the frame after the
// one last handed out, and waits until that one is taken.
class ReadAheadSource final : public FrameSource {
 public:
  explicit ReadAheadSource(std::unique_ptr<FrameSource> source)
      : source_(std::move(source)), worker_([this] { Work(); }) {
    Request();
  }

  ~ReadAheadSource() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    changed_.notify_all();
    worker_.join();
  }

  const SequenceInfo& info() const override { return source_->info(); }

  bool Next(StereoFrame* frame) override {
    ATTEND_CHECK(frame != nullptr) << "Next needs a frame to fill";
    Result result;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (ended_) {
        // The source ended at the last call; ask it again, as a caller of it would.
        requested_ = true;
        changed_.notify_all();
      }
      changed_.wait(lock, [this] { return ready_; });
      ready_ = false;
      result = std::move(result_);
      // Read on after a frame or a bad frame, not after the end.
      ended_ = !result.more;
      if (result.more) {
        requested_ = true;
        changed_.notify_all();
      }
    }
    if (result.error) std::rethrow_exception(result.error);
    if (!result.more) return false;
    *frame = std::move(result.frame);
    return true;
  }

 private:
  struct Result {
    StereoFrame frame;
    bool more = false;  // a frame (or a bad one) rather than the end
    std::exception_ptr error;
  };

  void Request() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      requested_ = true;
    }
    changed_.notify_all();
  }

  void Work() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      changed_.wait(lock, [this] { return quit_ || requested_; });
      if (quit_) return;
      requested_ = false;
      lock.unlock();
      Result result;
      try {
        result.more = source_->Next(&result.frame);
      } catch (...) {
        result.error = std::current_exception();
        result.more = true;
      }
      lock.lock();
      result_ = std::move(result);
      ready_ = true;
      changed_.notify_all();
    }
  }

  std::unique_ptr<FrameSource> source_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool requested_ = false;  // the worker is to read the next frame
  bool ready_ = false;      // result_ holds what it read, not yet taken
  bool ended_ = false;      // the last result taken was the end of the source
  bool quit_ = false;
  Result result_;
  std::thread worker_;  // last: starts once the members it uses exist
};

}  // namespace

std::unique_ptr<FrameSource> ReadAhead(std::unique_ptr<FrameSource> source) {
  ATTEND_CHECK(source != nullptr) << "ReadAhead needs a source";
  return std::make_unique<ReadAheadSource>(std::move(source));
}

}  // namespace attend
