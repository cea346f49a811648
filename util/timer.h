// Wall-clock timing of pipeline stages.
#pragma once

#include <chrono>
#include <ctime>
#include <string>
#include <utility>
#include <vector>

namespace attend {

// Milliseconds since construction (or the last Restart()).
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  void Restart() { start_ = std::chrono::steady_clock::now(); }
  double ElapsedMs() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_)
        .count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Per-stage times of one frame, in the order the stages ran (or any totals by name, in the
// order the names came: a run's detectors' searched pixels).
class StageTimes {
 public:
  void Add(const std::string& stage, double ms) {
    for (auto& [name, total] : stages_) {
      if (name == stage) {
        total += ms;
        return;
      }
    }
    stages_.emplace_back(stage, ms);
  }
  const std::vector<std::pair<std::string, double>>& stages() const { return stages_; }
  // The total of `stage`, 0 when it has none.
  double Get(const std::string& stage) const {
    for (const auto& [name, total] : stages_) {
      if (name == stage) return total;
    }
    return 0.0;
  }

 private:
  std::vector<std::pair<std::string, double>> stages_;
};

// The current time in UTC, as "2026-12-04T13:34:57Z".
inline std::string UtcTimestamp() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text;
}

}  // namespace attend
