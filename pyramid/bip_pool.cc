// BipPool (pyramid/bip.h): the buffers that the pyramids built one after another share.
#include <algorithm>
#include <memory>
#include <mutex>

#include "pyramid/bip.h"
#include "pyramid/bip_internal.h"

namespace attend {

size_t BipScratch::Bytes() const {
  size_t bytes = CapacityBytes(adjacency_offsets_) + CapacityBytes(adjacency_) +
                 CapacityBytes(son_offsets_) + CapacityBytes(sons_) + CapacityBytes(virtual_sons_) +
                 CapacityBytes(stamp_) + CapacityBytes(cell_row_) + CapacityBytes(cell_col_) +
                 CapacityBytes(row_orphans_) + CapacityBytes(linked_) + CapacityBytes(label_[0]) +
                 CapacityBytes(label_[1]) + CapacityBytes(roots_);
  for (const auto& plane : distance_) bytes += CapacityBytes(plane);
  for (const auto& plane : planes_) bytes += CapacityBytes(plane);
  return bytes;
}

namespace {

// The pixels a level set has room for: the capacity of its base's Hom.
size_t LevelCells(const std::vector<BipLevel>& levels) {
  return levels.empty() ? 0 : levels[0].hom.capacity();
}

size_t LevelBytes(const std::vector<BipLevel>& levels) {
  size_t bytes = 0;
  for (const BipLevel& level : levels) {
    bytes += CapacityBytes(level.hom) + CapacityBytes(level.feature) + CapacityBytes(level.area) +
             CapacityBytes(level.parent) + CapacityBytes(level.edges);
  }
  return bytes;
}

}  // namespace

BipPool::BipPool() = default;
BipPool::~BipPool() = default;

std::unique_ptr<BipScratch> BipPool::TakeScratch(size_t cells) {
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if (cells >= kLargeCells) {
      // A build holds its scratch for a few milliseconds and takes nothing else meanwhile, so
      // the wait ends.
      scratch_returned_.wait(lock, [this] { return large_lent_ == 0; });
      ++large_lent_;
      most_large_lent_ = std::max(most_large_lent_, large_lent_);
    }
    // The large scratch is kept apart, for large builds only: a small build that took it
    // would leave the next large build to grow a second one.
    if (cells >= kLargeCells && large_idle_ != nullptr) return std::move(large_idle_);
    if (!idle_scratch_.empty()) {
      // Otherwise a large build takes the largest small scratch, which it grows, and a small
      // build the smallest.
      const auto by_bytes = [](const auto& a, const auto& b) { return a->Bytes() < b->Bytes(); };
      const auto chosen =
          cells >= kLargeCells
              ? std::max_element(idle_scratch_.begin(), idle_scratch_.end(), by_bytes)
              : std::min_element(idle_scratch_.begin(), idle_scratch_.end(), by_bytes);
      std::unique_ptr<BipScratch> scratch = std::move(*chosen);
      idle_scratch_.erase(chosen);
      return scratch;
    }
  }
  return std::make_unique<BipScratch>();
}

void BipPool::GiveScratch(std::unique_ptr<BipScratch> scratch, size_t cells) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (cells < kLargeCells) {
      idle_scratch_.push_back(std::move(scratch));
      return;
    }
    large_idle_ = std::move(scratch);  // the one large scratch: none was idle while it was lent
    --large_lent_;
  }
  scratch_returned_.notify_all();
}

std::unique_ptr<BipPool::Levels> BipPool::TakeLevels(size_t cells) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // The smallest set with room, unless it is far larger than needed (a crop of a tracker
    // would otherwise hold a whole frame's set); else the largest one without room, which
    // grows; else a new one.
    int fit = -1, grow = -1;
    for (int i = 0; i < static_cast<int>(idle_levels_.size()); ++i) {
      const size_t room = LevelCells(*idle_levels_[i]);
      if (room >= cells) {
        if (room <= 4 * cells + 4096 && (fit < 0 || room < LevelCells(*idle_levels_[fit]))) {
          fit = i;
        }
      } else if (grow < 0 || room > LevelCells(*idle_levels_[grow])) {
        grow = i;
      }
    }
    const int chosen = fit >= 0 ? fit : grow;
    if (chosen >= 0) {
      std::unique_ptr<Levels> levels = std::move(idle_levels_[chosen]);
      idle_levels_.erase(idle_levels_.begin() + chosen);
      return levels;
    }
  }
  return std::make_unique<Levels>();
}

void BipPool::GiveLevels(std::unique_ptr<Levels> levels) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (static_cast<int>(idle_levels_.size()) < kMaxIdleLevelSets) {
    idle_levels_.push_back(std::move(levels));
    return;
  }
  // Keep the larger sets: they are the costly ones to make again.
  auto smallest = std::min_element(
      idle_levels_.begin(), idle_levels_.end(),
      [](const auto& a, const auto& b) { return LevelCells(*a) < LevelCells(*b); });
  if (LevelCells(**smallest) < LevelCells(*levels)) *smallest = std::move(levels);
}

size_t BipPool::IdleBytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  size_t bytes = IdleScratchBytesLocked();
  for (const auto& levels : idle_levels_) bytes += LevelBytes(*levels);
  return bytes;
}

int BipPool::MostLargeScratchesLent() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return most_large_lent_;
}

size_t BipPool::IdleScratchBytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return IdleScratchBytesLocked();
}

size_t BipPool::IdleScratchBytesLocked() const {
  size_t bytes = 0;
  for (const auto& scratch : idle_scratch_) bytes += scratch->Bytes();
  if (large_idle_ != nullptr) bytes += large_idle_->Bytes();
  return bytes;
}

int BipPool::IdleScratches() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(idle_scratch_.size()) + (large_idle_ != nullptr ? 1 : 0);
}

int BipPool::IdleLevelSets() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(idle_levels_.size());
}

void BipPool::Clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  idle_scratch_.clear();
  large_idle_.reset();
  idle_levels_.clear();
}

}  // namespace attend
