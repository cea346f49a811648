// One call at a time on a stateful object of the Python module (attend.Pipeline, attend.Tracker,
// a feature's context): the C++ objects underneath are not thread-safe, and their calls
// release the GIL, so two Python threads on one object used to run into each other (issue 46:
// two threads on one Pipeline, or reset() during process(), killed the interpreter). A second
// call while one runs is refused with InUseError instead of being queued: sharing an object
// between threads is a mistake to be told of, not a slowdown to be hidden (docs/PYTHON.md,
// "Threads").
#pragma once

#include <chrono>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "util/error.h"

namespace attend::python {

// An object used by a second call while one runs (attend.InUseError, a usage error: status 2).
class InUseError : public Error {
 public:
  explicit InUseError(const std::string& message) : Error(ExitStatus::kUsage, message) {}
};

// The state of one object: which call runs, on which thread, since when.
class InUse {
 public:
  // `what` names the object in messages ("attend.Pipeline"); `advice` ends them.
  InUse(std::string what, std::string advice)
      : what_(std::move(what)), advice_(std::move(advice)) {}
  InUse(const InUse&) = delete;
  InUse& operator=(const InUse&) = delete;

  // Marks the object as running `method` ("process()") until the scope ends; InUseError when
  // another call runs, on this thread (a call from inside a call: a feature's compute() that
  // calls its own pipeline) or another.
  class Scope {
   public:
    Scope(InUse* in_use, const char* method) : in_use_(in_use) { in_use_->Enter(method); }
    ~Scope() { in_use_->Leave(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    InUse* in_use_;
  };

 private:
  void Enter(const char* method) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (method_ != nullptr) {
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - since_).count();
      char elapsed[32];
      std::snprintf(elapsed, sizeof elapsed, "%.2f s", seconds);
      const bool same = owner_ == std::this_thread::get_id();
      throw InUseError("this " + what_ + " is in use " +
                       (same ? std::string("by this same thread, from inside its own ")
                             : std::string("by another thread (")) +
                       method_ + (same ? ", " : " ") + "since " + elapsed + " ago" +
                       (same ? "" : ")") + ": " + std::string(method) + " cannot run beside it; " +
                       advice_);
    }
    method_ = method;
    owner_ = std::this_thread::get_id();
    since_ = std::chrono::steady_clock::now();
  }

  void Leave() {
    const std::lock_guard<std::mutex> lock(mutex_);
    method_ = nullptr;
  }

  const std::string what_;
  const std::string advice_;
  std::mutex mutex_;
  const char* method_ = nullptr;  // the call running; nullptr when none
  std::thread::id owner_;
  std::chrono::steady_clock::time_point since_;
};

}  // namespace attend::python
