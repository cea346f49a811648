#include "pyramid/bip.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <mutex>

#include "util/error.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// The 8-neighbourhood, in raster order; ties between equally similar neighbours go to the
// first one in this order.
constexpr int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
constexpr int kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

inline float Distance2(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

inline uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<uint64_t>(std::min(a, b));
  const auto hi = static_cast<uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

constexpr float kFar = std::numeric_limits<float>::infinity();

// Keeps the most similar candidate seen so far (the first of equals). Written without a
// branch: which neighbour is closest is unpredictable in textured areas.
struct Best {
  int id = -1;
  float distance2 = kFar;
  void Offer(int candidate, float d2) {
    const bool closer = d2 < distance2;
    distance2 = closer ? d2 : distance2;
    id = closer ? candidate : id;
  }
};

// The squared distance stored for a pair of cells of which one is a hole (Hom = 0): the NaN
// whose bits are all ones, which no arithmetic produces. It fails every "< threshold" test.
constexpr uint32_t kHoleBits = ~uint32_t{0};

// A neighbour of the 8-neighbourhood as one integer: its squared distance above its position
// (0..7, raster order). The bits of non-negative floats order like their values, so the
// smallest key is the most similar neighbour and, among equals, the first in raster order;
// comparing integers lets the choice run without branches and with short dependency chains.
// Keys from kNoNeighbour up (a hole's, or none) stand for no neighbour.
constexpr uint64_t kNoNeighbour = uint64_t{kHoleBits} << 3;
inline uint64_t NeighbourKey(float d2, int position) {
  return (uint64_t{std::bit_cast<uint32_t>(d2)} << 3) | static_cast<uint64_t>(position);
}

// The loops over whole planes below are compiled for AVX2 and for SSE2, with the same results
// (util/vector_clones.h).

// Interleaved 3-float features to one plane per component.
ATTEND_VECTOR_CLONES void SplitPlanes(const float* __restrict feature, size_t count,
                                      float* __restrict p0, float* __restrict p1,
                                      float* __restrict p2) {
  for (size_t i = 0; i < count; ++i) {
    p0[i] = feature[3 * i];
    p1[i] = feature[3 * i + 1];
    p2[i] = feature[3 * i + 2];
  }
}

// d[i] = |f(i) - f(i + offset)|^2 for i in [begin, end), f given as three planes.
ATTEND_VECTOR_CLONES void PlaneDistances(const float* p0, const float* p1, const float* p2,
                                         size_t begin, size_t end, size_t offset,
                                         float* __restrict d) {
  for (size_t i = begin; i < end; ++i) {
    const float a = p0[i] - p0[i + offset], b = p1[i] - p1[i + offset], c = p2[i] - p2[i + offset];
    d[i] = a * a + b * b + c * c;
  }
}

// d[i] = the hole marker for i in [begin, end) where cell i or i + offset is a hole.
ATTEND_VECTOR_CLONES void MarkHoles(const uint8_t* hom, size_t begin, size_t end, size_t offset,
                                    float* __restrict d) {
  const float hole = std::bit_cast<float>(kHoleBits);
  for (size_t i = begin; i < end; ++i) d[i] = (hom[i] & hom[i + offset]) != 0 ? d[i] : hole;
}

// The area-weighted feature sums of `count` vertices to means. Holes (area 0) keep their zero
// feature: they are multiplied by 1 rather than skipped, so that the loop vectorises.
ATTEND_VECTOR_CLONES void DivideByArea(const int32_t* __restrict area, int count,
                                       float* __restrict feature) {
  for (int id = 0; id < count; ++id) {
    const float inverse = 1.f / static_cast<float>(area[id] + (area[id] == 0));
    feature[3 * id] *= inverse;
    feature[3 * id + 1] *= inverse;
    feature[3 * id + 2] *= inverse;
  }
}

// Resizes to n, allocating exactly n when the capacity is short: a vector grown by resize()
// alone doubles, and these are the largest buffers of a frame.
template <typename T>
void Fit(std::vector<T>* v, size_t n) {
  if (v->capacity() < n) v->reserve(n);
  v->resize(n);
}

template <typename T>
size_t CapacityBytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

}  // namespace

struct BipScratch {
  // CSR adjacency of the current level's explicit edges, over all ids.
  std::vector<int32_t> adjacency_offsets_;
  std::vector<int32_t> adjacency_;
  // Squared distances between each cell of the current level and its east, south, south-east
  // and south-west neighbours: computed once, read by decimation and by the orphans.
  std::vector<float> distance_[4];
  std::vector<float> planes_[3];  // the current level's features, one plane per component
  // The sons of each virtual vertex of the level being built (CSR), and a stamp per vertex.
  std::vector<int32_t> son_offsets_;
  std::vector<int32_t> sons_;
  std::vector<int32_t> virtual_sons_;  // ungrouped
  std::vector<int32_t> stamp_;
  // Row and column of each cell of the level being built (variant edges).
  std::vector<int32_t> cell_row_;
  std::vector<int32_t> cell_col_;
  // Columns of the orphans of one row, for stage 2.
  std::vector<int32_t> row_orphans_;
  // Vertices of the current level linked to a parent by stages 2 and 3.
  std::vector<int32_t> linked_;
  // Bip::LabelRoots.
  std::vector<int32_t> label_[2];
  std::vector<Bip::VertexRef> roots_;

  size_t Bytes() const {
    size_t bytes = CapacityBytes(adjacency_offsets_) + CapacityBytes(adjacency_) +
                   CapacityBytes(son_offsets_) + CapacityBytes(sons_) +
                   CapacityBytes(virtual_sons_) + CapacityBytes(stamp_) +
                   CapacityBytes(cell_row_) + CapacityBytes(cell_col_) +
                   CapacityBytes(row_orphans_) + CapacityBytes(linked_) +
                   CapacityBytes(label_[0]) + CapacityBytes(label_[1]) + CapacityBytes(roots_);
    for (const auto& plane : distance_) bytes += CapacityBytes(plane);
    for (const auto& plane : planes_) bytes += CapacityBytes(plane);
    return bytes;
  }
};

namespace {

// The pixels a level set has room for: the capacity of its base's Hom.
size_t LevelCells(const std::vector<BipLevel>& levels) {
  return levels.empty() ? 0 : levels[0].hom.capacity();
}

size_t LevelBytes(const std::vector<BipLevel>& levels) {
  size_t bytes = 0;
  for (const BipLevel& level : levels) {
    bytes += CapacityBytes(level.hom) + CapacityBytes(level.feature) +
             CapacityBytes(level.area) + CapacityBytes(level.parent) +
             CapacityBytes(level.edges);
  }
  return bytes;
}

}  // namespace

BipPool::BipPool() = default;
BipPool::~BipPool() = default;

BipPool& BipPool::Shared() {
  // Never destroyed: builders in objects with static storage may give buffers back at exit.
  static BipPool* const pool = new BipPool();
  return *pool;
}

std::unique_ptr<BipScratch> BipPool::TakeScratch() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (!idle_scratch_.empty()) {
      std::unique_ptr<BipScratch> scratch = std::move(idle_scratch_.back());
      idle_scratch_.pop_back();
      return scratch;
    }
  }
  return std::make_unique<BipScratch>();
}

void BipPool::GiveScratch(std::unique_ptr<BipScratch> scratch) {
  const std::lock_guard<std::mutex> lock(mutex_);
  idle_scratch_.push_back(std::move(scratch));
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
        if (room <= 4 * cells + 4096 &&
            (fit < 0 || room < LevelCells(*idle_levels_[fit]))) {
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
  size_t bytes = 0;
  for (const auto& scratch : idle_scratch_) bytes += scratch->Bytes();
  for (const auto& levels : idle_levels_) bytes += LevelBytes(*levels);
  return bytes;
}

int BipPool::IdleScratches() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(idle_scratch_.size());
}

int BipPool::IdleLevelSets() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(idle_levels_.size());
}

void BipPool::Clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  idle_scratch_.clear();
  idle_levels_.clear();
}

const OptionFields<BipOptions>& BipOptions::Fields() {
  using O = BipOptions;
  static const OptionFields<BipOptions> fields = {
      {"link_across_kinds", &O::link_across_kinds,
       "orphans also link to and twine with neighbours of the other kind (not the thesis's)"},
      CodeOnly<O>({"max_levels", &O::max_levels, Range::Closed(1, 1e6),
                   "a bound on the number of levels"})};
  return fields;
}

std::string BipOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

int BipLevel::CountRegular() const { return num_regular; }

BipBuilder::BipBuilder(BipOptions options, BipPool* pool) : options_(options), pool_(pool) {
  const std::string problem = options_.Check();
  ATTEND_CHECK(problem.empty()) << problem;
  ATTEND_CHECK(pool_ != nullptr) << "a BipBuilder needs a pool";
  bip_.pool_ = pool_;
}

BipBuilder::~BipBuilder() { Release(); }

void BipBuilder::Release() {
  if (levels_ != nullptr) pool_->GiveLevels(std::move(levels_));
  bip_.levels_ = nullptr;
  bip_.num_levels_ = 0;
}

int BipBuilder::AdjacencyBegin(int id) const {
  return scratch_->adjacency_.empty() ? 0 : scratch_->adjacency_offsets_[id];
}

int BipBuilder::AdjacencyEnd(int id) const {
  return scratch_->adjacency_.empty() ? 0 : scratch_->adjacency_offsets_[id + 1];
}

const Bip& BipBuilder::Build(const cv::Mat& features, const SimilarityPolicy& policy,
                             const cv::Mat& mask, int schedule_side) {
  ATTEND_CHECK(features.type() == CV_32FC3 && !features.empty())
      << "BIP features must be a non-empty CV_32FC3 image";
  ATTEND_CHECK(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == features.size()))
      << "the BIP mask must be CV_8UC1 of the features' size";
  const int width = features.cols, height = features.rows;
  const size_t cells = static_cast<size_t>(width) * height;
  if (levels_ == nullptr) levels_ = pool_->TakeLevels(cells);
  if (levels_->empty()) levels_->resize(1);
  // The scratch goes back to the pool however the build ends.
  struct ScratchLease {
    BipPool* pool;
    BipScratch** held;
    std::unique_ptr<BipScratch> scratch;
    ~ScratchLease() {
      *held = nullptr;
      pool->GiveScratch(std::move(scratch));
    }
  } lease{pool_, &scratch_, pool_->TakeScratch()};
  scratch_ = lease.scratch.get();

  BipLevel& base = (*levels_)[0];
  base.cols = width;
  base.rows = height;
  base.num_virtual = 0;
  base.num_regular = 0;
  Fit(&base.hom, cells);
  Fit(&base.area, cells);
  Fit(&base.parent, cells);
  std::fill(base.parent.begin(), base.parent.end(), -1);
  Fit(&base.feature, 3 * cells);
  base.edges.clear();
  for (int row = 0; row < height; ++row) {
    const float* in = features.ptr<float>(row);
    std::copy(in, in + 3 * width, base.feature.begin() + 3 * static_cast<size_t>(row) * width);
  }
  if (mask.empty()) {
    std::fill(base.hom.begin(), base.hom.end(), 1);
    std::fill(base.area.begin(), base.area.end(), 1);
    base.num_regular = static_cast<int>(cells);
  } else {
    for (int row = 0; row < height; ++row) {
      const uchar* inside = mask.ptr<uchar>(row);
      for (int col = 0; col < width; ++col) {
        const uint8_t hom = inside[col] != 0 ? 1 : 0;
        base.hom[static_cast<size_t>(row) * width + col] = hom;
        base.area[static_cast<size_t>(row) * width + col] = hom;
        base.num_regular += hom;
      }
    }
  }

  bip_.levels_ = levels_.get();
  bip_.width_ = width;
  bip_.height_ = height;
  const int side = schedule_side > 0 ? schedule_side : std::min(width, height);
  bip_.top_regular_level_ = static_cast<int>(std::floor(std::log2(side)));
  bip_.thresholds_.clear();
  bip_.num_levels_ = 1;
  for (int l = 0; l + 1 < options_.max_levels; ++l) {
    const float threshold = policy.Threshold(l, bip_.top_regular_level_);
    bip_.thresholds_.push_back(threshold);
    BuildLevel(l, threshold);
    const BipLevel& up = (*levels_)[l + 1];
    if (up.num_virtual == 0 && up.num_regular == 0) break;  // the stop rule
    bip_.num_levels_ = l + 2;
  }
  return bip_;
}

void BipBuilder::BuildLevel(int l, float threshold) {
  if (static_cast<int>(levels_->size()) < l + 2) levels_->resize(l + 2);
  BipLevel& up = (*levels_)[l + 1];
  const BipLevel& cur = (*levels_)[l];
  up.cols = cur.cols / 2;
  up.rows = cur.rows / 2;
  up.num_virtual = 0;
  up.num_regular = 0;
  const size_t cells = static_cast<size_t>(up.cols) * up.rows;
  // Regular decimation writes every cell's Hom, area and feature.
  Fit(&up.hom, cells);
  Fit(&up.area, cells);
  Fit(&up.parent, cells);
  std::fill(up.parent.begin(), up.parent.end(), -1);
  Fit(&up.feature, 3 * cells);
  up.edges.clear();

  const float t2 = threshold * threshold;
  scratch_->linked_.clear();
  NeighbourDistances(l);
  RegularDecimation(l, t2);  // stage 1
  BuildAdjacency(l);
  RegularOrphans(l, t2);  // stage 2
  VirtualOrphans(l, t2);  // stage 3
  // The virtual vertices made by stages 2 and 3, each with a zero feature sum and area and
  // no parent yet; added at once, so that the level's arrays are allocated to their size.
  const size_t ids = static_cast<size_t>(up.num_ids());
  Fit(&up.feature, 3 * ids);
  Fit(&up.area, ids);
  Fit(&up.parent, ids);
  std::fill(up.feature.begin() + 3 * cells, up.feature.end(), 0.f);
  std::fill(up.area.begin() + cells, up.area.end(), 0);
  std::fill(up.parent.begin() + cells, up.parent.end(), -1);
  UpdateParents(l);
  IntraLevelEdges(l);  // stage 4
}

enum Direction { kEast = 0, kSouth = 1, kSouthEast = 2, kSouthWest = 3 };

void BipBuilder::NeighbourDistances(int l) {
  const BipLevel& cur = (*levels_)[l];
  const int cols = cur.cols, rows = cur.rows;
  const size_t cells = static_cast<size_t>(cols) * rows;
  // Grow only: resizing back up after a smaller level would zero-fill every frame.
  for (auto& plane : scratch_->distance_) {
    if (plane.size() < cells) Fit(&plane, cells);
  }
  if (cells == 0) return;  // a 1-wide level halves to 0 columns
  // One plane per feature component, so that the loops below vectorise.
  for (auto& plane : scratch_->planes_) {
    if (plane.size() < cells) Fit(&plane, cells);
  }
  const float* p0 = scratch_->planes_[0].data();
  const float* p1 = scratch_->planes_[1].data();
  const float* p2 = scratch_->planes_[2].data();
  SplitPlanes(cur.feature.data(), cells, scratch_->planes_[0].data(), scratch_->planes_[1].data(), scratch_->planes_[2].data());
  // With holes, a pair with a hole gets kHoleBits, so that stage 2 need not look at Hom.
  const bool holes = cur.num_regular < static_cast<int>(cells);
  auto distances = [&](float* d, size_t begin, size_t end, size_t offset) {
    PlaneDistances(p0, p1, p2, begin, end, offset, d);
    if (holes) MarkHoles(cur.hom.data(), begin, end, offset, d);
  };
  float* east = scratch_->distance_[kEast].data();
  float* south = scratch_->distance_[kSouth].data();
  float* south_east = scratch_->distance_[kSouthEast].data();
  float* south_west = scratch_->distance_[kSouthWest].data();
  // Whole-plane passes; the entries that wrap around a row end are overwritten below.
  distances(east, 0, cells - 1, 1);
  east[cells - 1] = kFar;
  const size_t last_row = cells - cols;
  distances(south, 0, last_row, cols);
  if (last_row > 0) {
    distances(south_east, 0, last_row - 1, cols + 1);
    distances(south_west, 1, last_row, cols - 1);
  }
  std::fill(south + last_row, south + cells, kFar);
  std::fill(south_east + (last_row > 0 ? last_row - 1 : 0), south_east + cells, kFar);
  std::fill(south_west + last_row, south_west + cells, kFar);
  for (int row = 0; row < rows; ++row) {
    const size_t first = static_cast<size_t>(row) * cols;
    east[first + cols - 1] = kFar;
    south_east[first + cols - 1] = kFar;
    south_west[first] = kFar;
  }
}

// Stage 1: (i, j, l+1) is a regular vertex iff its four sons are regular and pairwise similar.
// Its area and (not yet divided) feature sum are set here. Every cell of l + 1 is written, and
// every window's sons get their parent or -1 (which they hold already), without a branch:
// which windows pass is unpredictable in textured areas.
void BipBuilder::RegularDecimation(int l, float t2) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  const float* east = scratch_->distance_[kEast].data();
  const float* south = scratch_->distance_[kSouth].data();
  const float* south_east = scratch_->distance_[kSouthEast].data();
  const float* south_west = scratch_->distance_[kSouthWest].data();
  // Plain pointers and a local count: the Hom bytes written below may alias anything, which
  // would make the compiler reload every vector's data and the count after each window.
  const float* son_feature = cur.feature.data();
  const int32_t* son_area = cur.area.data();
  int32_t* son_parent = (*levels_)[l].parent.data();
  uint8_t* hom = up.hom.data();
  int32_t* area = up.area.data();
  float* feature = up.feature.data();
  const int cols = cur.cols;
  int regulars = 0;
  for (int row = 0; row < up.rows; ++row) {
    for (int col = 0; col < up.cols; ++col) {
      const int a = 2 * row * cols + 2 * col;
      const int b = a + 1, c = a + cols, d = c + 1;
      // The six pairs of the 2x2 window are similar; this fails when a son is a hole, as its
      // distances are the hole marker.
      const bool regular = (east[a] < t2) & (east[c] < t2) & (south[a] < t2) & (south[b] < t2) &
                           (south_east[a] < t2) & (south_west[b] < t2);
      const int id = row * up.cols + col;
      float sum[3] = {0.f, 0.f, 0.f};
      int sum_area = 0;
      for (int son : {a, b, c, d}) {
        son_parent[son] = regular ? id : -1;
        const float weight = static_cast<float>(son_area[son]);
        const float* f = son_feature + 3 * static_cast<size_t>(son);
        sum[0] += weight * f[0];
        sum[1] += weight * f[1];
        sum[2] += weight * f[2];
        sum_area += son_area[son];
      }
      hom[id] = regular;
      regulars += regular;
      area[id] = regular ? sum_area : 0;
      for (int k = 0; k < 3; ++k) feature[3 * static_cast<size_t>(id) + k] = regular ? sum[k] : 0.f;
    }
  }
  up.num_regular = regulars;
}

void BipBuilder::BuildAdjacency(int l) {
  const BipLevel& cur = (*levels_)[l];
  if (cur.edges.empty()) {  // level 0, and levels without virtual vertices
    scratch_->adjacency_offsets_.clear();
    scratch_->adjacency_.clear();
    return;
  }
  const int ids = cur.num_ids();
  scratch_->adjacency_offsets_.assign(ids + 1, 0);
  for (uint64_t key : cur.edges) {
    ++scratch_->adjacency_offsets_[(key >> 32) + 1];
    ++scratch_->adjacency_offsets_[(key & 0xffffffffu) + 1];
  }
  for (int i = 0; i < ids; ++i) scratch_->adjacency_offsets_[i + 1] += scratch_->adjacency_offsets_[i];
  scratch_->adjacency_.resize(2 * cur.edges.size());
  scratch_->stamp_.assign(scratch_->adjacency_offsets_.begin(), scratch_->adjacency_offsets_.end() - 1);  // fill cursor
  for (uint64_t key : cur.edges) {
    const auto a = static_cast<int32_t>(key >> 32), b = static_cast<int32_t>(key & 0xffffffffu);
    scratch_->adjacency_[scratch_->stamp_[a]++] = b;
    scratch_->adjacency_[scratch_->stamp_[b]++] = a;
  }
}

int BipBuilder::NewVirtual(BipLevel* up) {
  // Its feature, area and parent are added once the stages that make them are done.
  const int id = up->num_cells() + up->num_virtual;
  ++up->num_virtual;
  return id;
}

// The decision shared by stages 2 and 3: the parent of the most similar neighbour that has
// one (conditions 1 and 3), else a new virtual parent shared with the most similar orphan
// neighbour (conditions 2 and 3), each only below the threshold.
void BipBuilder::Link(int l, int id, int parented, float parented_d2, int orphan, float orphan_d2,
                      float t2) {
  BipLevel& cur = (*levels_)[l];
  if (parented_d2 < t2) {
    cur.parent[id] = cur.parent[parented];
    scratch_->linked_.push_back(id);
  } else if (orphan_d2 < t2) {
    const int fresh = NewVirtual(&(*levels_)[l + 1]);
    cur.parent[id] = fresh;
    cur.parent[orphan] = fresh;
    scratch_->linked_.push_back(id);
    scratch_->linked_.push_back(orphan);
  }
}

// Stage 2, in raster order: parent search (condition 1), else intra-level twining
// (condition 2).
// Longer than most on purpose: the raster scan applies the thesis's conditions 1 and 2 to
// each orphan in turn, each reading what the earlier ones of the scan linked.
void BipBuilder::RegularOrphans(int l, float t2) {
  BipLevel& cur = (*levels_)[l];
  const bool across = options_.link_across_kinds;
  const float* east = scratch_->distance_[kEast].data();
  const float* south = scratch_->distance_[kSouth].data();
  const float* south_east = scratch_->distance_[kSouthEast].data();
  const float* south_west = scratch_->distance_[kSouthWest].data();
  const int cols = cur.cols;
  const int grid[8] = {-cols - 1, -cols, -cols + 1, -1, 1, cols - 1, cols, cols + 1};
  // The most similar neighbour among those of one kind, from its key.
  // Both are chosen rather than branched on: whether there is one is unpredictable.
  auto best_of = [&](int id, uint64_t key) {
    const bool found = key < kNoNeighbour;
    Best best;
    best.id = found ? id + grid[key & 7] : -1;
    best.distance2 = found ? std::bit_cast<float>(static_cast<uint32_t>(key >> 3)) : kFar;
    return best;
  };
  scratch_->row_orphans_.resize(cols);
  for (int row = 0; row < cur.rows; ++row) {
    // The row's orphans, gathered without a branch per cell: whether a cell is an orphan
    // alternates unpredictably in textured areas.
    const int first = row * cols;
    int count = 0;
    for (int col = 0; col < cols; ++col) {
      scratch_->row_orphans_[count] = col;
      count += (cur.hom[first + col] != 0) & (cur.parent[first + col] < 0);
    }
    for (int k = 0; k < count; ++k) {
      const int col = scratch_->row_orphans_[k];
      const int id = first + col;
      if (cur.parent[id] >= 0) continue;  // twinned earlier in this row
      Best parented, orphan;
      if (row > 0 && col > 0 && row + 1 < cur.rows && col + 1 < cols) {
        // The squared distances to the neighbours, in the order of `grid`.
        float d2[8];
        d2[0] = south_east[id - cols - 1];
        d2[1] = south[id - cols];
        d2[2] = south_west[id - cols + 1];
        d2[3] = east[id - 1];
        d2[4] = east[id];
        d2[5] = south_west[id];
        d2[6] = south[id];
        d2[7] = south_east[id];
        uint64_t parented_key = kNoNeighbour, orphan_key = kNoNeighbour;
        for (int k = 0; k < 8; ++k) {
          // A hole's distance is kHoleBits: its key is no neighbour.
          const uint64_t key = NeighbourKey(d2[k], k);
          const bool has_parent = cur.parent[id + grid[k]] >= 0;
          parented_key = std::min(parented_key, has_parent ? key : kNoNeighbour);
          orphan_key = std::min(orphan_key, has_parent ? kNoNeighbour : key);
        }
        parented = best_of(id, parented_key);
        orphan = best_of(id, orphan_key);
      } else {
        // On the border, in raster order of the neighbours so that ties go to the first.
        auto offer = [&](int n, float d2) {
          if (cur.hom[n] == 0) return;
          if (cur.parent[n] >= 0) {
            parented.Offer(n, d2);
          } else {
            orphan.Offer(n, d2);
          }
        };
        if (row > 0 && col > 0) offer(id - cols - 1, south_east[id - cols - 1]);
        if (row > 0) offer(id - cols, south[id - cols]);
        if (row > 0 && col + 1 < cols) offer(id - cols + 1, south_west[id - cols + 1]);
        if (col > 0) offer(id - 1, east[id - 1]);
        if (col + 1 < cols) offer(id + 1, east[id]);
        if (row + 1 < cur.rows && col > 0) offer(id + cols - 1, south_west[id]);
        if (row + 1 < cur.rows) offer(id + cols, south[id]);
        if (row + 1 < cur.rows && col + 1 < cols) offer(id + cols + 1, south_east[id]);
      }
      if (across) {
        const float* colour = cur.Feature(id);
        for (int e = AdjacencyBegin(id); e < AdjacencyEnd(id); ++e) {
          const int n = scratch_->adjacency_[e];
          const float d2 = Distance2(colour, cur.Feature(n));
          if (cur.parent[n] >= 0) {
            parented.Offer(n, d2);
          } else {
            orphan.Offer(n, d2);
          }
        }
      }
      Link(l, id, parented.id, parented.distance2, orphan.id, orphan.distance2, t2);
    }
  }
}

// Stage 3, in order of creation: virtual parent search, else virtual linking (condition 3).
void BipBuilder::VirtualOrphans(int l, float t2) {
  BipLevel& cur = (*levels_)[l];
  const bool across = options_.link_across_kinds;
  for (int id = cur.num_cells(); id < cur.num_ids(); ++id) {
    if (cur.parent[id] >= 0) continue;
    const float* colour = cur.Feature(id);
    Best parented, orphan;
    for (int e = AdjacencyBegin(id); e < AdjacencyEnd(id); ++e) {
      const int n = scratch_->adjacency_[e];
      const bool is_virtual = cur.IsVirtual(n);
      if (!is_virtual && !across) continue;
      const float d2 = Distance2(colour, cur.Feature(n));
      if (cur.parent[n] >= 0) {
        parented.Offer(n, d2);
      } else {
        orphan.Offer(n, d2);  // a regular orphan only with link_across_kinds
      }
    }
    Link(l, id, parented.id, parented.distance2, orphan.id, orphan.distance2, t2);
  }
}

// Area-weighted means of the sons: the parents' features and areas. Decimation already
// summed the regular parents' four sons; the sons linked in stages 2 and 3 are added here.
void BipBuilder::UpdateParents(int l) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  for (int id : scratch_->linked_) {
    const int p = cur.parent[id];
    const float weight = static_cast<float>(cur.area[id]);
    const float* son = cur.Feature(id);
    float* sum = &up.feature[3 * static_cast<size_t>(p)];
    sum[0] += weight * son[0];
    sum[1] += weight * son[1];
    sum[2] += weight * son[2];
    up.area[p] += cur.area[id];
  }
  DivideByArea(up.area.data(), up.num_ids(), up.feature.data());
}

// Variant only: two regular vertices of l + 1 whose reduction windows touch although their
// cells are not adjacent in the array. Parent search grows a regular parent's window past its
// 2x2 block, so this happens; the thesis leaves such pairs implicit, that is unconnected.
void BipBuilder::DistantRegularEdges(int l) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  const int first_virtual = up.num_cells();
  // Row and column of every cell of l + 1, so that the test below needs no division.
  scratch_->cell_row_.resize(first_virtual);
  scratch_->cell_col_.resize(first_virtual);
  for (int row = 0, id = 0; row < up.rows; ++row) {
    for (int col = 0; col < up.cols; ++col, ++id) {
      scratch_->cell_row_[id] = row;
      scratch_->cell_col_[id] = col;
    }
  }
  auto add = [&](int p, int q) {
    if (p < 0 || q < 0 || p == q || p >= first_virtual || q >= first_virtual) return;
    if (std::abs(scratch_->cell_row_[p] - scratch_->cell_row_[q]) <= 1 && std::abs(scratch_->cell_col_[p] - scratch_->cell_col_[q]) <= 1) {
      return;  // implicit in the array
    }
    up.edges.push_back(EdgeKey(p, q));
  };
  // Sons that joined a regular parent by parent search, with their grid and explicit
  // neighbours; decimation sons of two parents are only ever array neighbours. The sons are
  // grouped by parent (counting sort) and a stamp per neighbour parent skips repeats, so each
  // pair is pushed at most once from each side.
  scratch_->son_offsets_.assign(first_virtual + 1, 0);
  for (int id : scratch_->linked_) {
    if (cur.parent[id] < first_virtual) ++scratch_->son_offsets_[cur.parent[id] + 1];
  }
  for (int p = 0; p < first_virtual; ++p) scratch_->son_offsets_[p + 1] += scratch_->son_offsets_[p];
  scratch_->sons_.resize(scratch_->son_offsets_[first_virtual]);
  scratch_->stamp_.assign(scratch_->son_offsets_.begin(), scratch_->son_offsets_.end() - 1);  // fill cursor
  for (int id : scratch_->linked_) {
    if (cur.parent[id] < first_virtual) scratch_->sons_[scratch_->stamp_[cur.parent[id]]++] = id;
  }
  scratch_->stamp_.assign(first_virtual, -1);
  const int cols = cur.cols, rows = cur.rows;
  const int grid[8] = {-cols - 1, -cols, -cols + 1, -1, 1, cols - 1, cols, cols + 1};
  for (int p = 0; p < first_virtual; ++p) {
    if (scratch_->son_offsets_[p] == scratch_->son_offsets_[p + 1]) continue;
    const int p_row = scratch_->cell_row_[p], p_col = scratch_->cell_col_[p];
    // Cheapest and most selective tests first: most neighbours have no parent, a virtual one,
    // p or an array neighbour of p, none of which makes an edge here.
    auto visit = [&](int neighbour) {
      const int q = cur.parent[neighbour];
      if (static_cast<unsigned>(q) >= static_cast<unsigned>(first_virtual)) return;
      if (std::abs(scratch_->cell_row_[q] - p_row) <= 1 && std::abs(scratch_->cell_col_[q] - p_col) <= 1) return;
      if (scratch_->stamp_[q] == p) return;
      scratch_->stamp_[q] = p;
      up.edges.push_back(EdgeKey(p, q));
    };
    for (int k = scratch_->son_offsets_[p]; k < scratch_->son_offsets_[p + 1]; ++k) {
      const int id = scratch_->sons_[k];
      if (!cur.IsVirtual(id)) {
        const int row = id / cols, col = id - row * cols;
        if (row > 0 && col > 0 && row + 1 < rows && col + 1 < cols) {
          for (int d = 0; d < 8; ++d) visit(id + grid[d]);
        } else {
          for (int d = 0; d < 8; ++d) {
            const int x = col + kDx[d], y = row + kDy[d];
            if (x >= 0 && y >= 0 && x < cols && y < rows) visit(y * cols + x);
          }
        }
      }
      for (int e = AdjacencyBegin(id); e < AdjacencyEnd(id); ++e) visit(scratch_->adjacency_[e]);
    }
  }
  // Explicit edges of level l between any two sons.
  for (uint64_t key : cur.edges) add(cur.parent[key >> 32], cur.parent[key & 0xffffffffu]);
  std::sort(up.edges.begin(), up.edges.end());
  up.edges.erase(std::unique(up.edges.begin(), up.edges.end()), up.edges.end());
}

// Stage 4: two vertices of l + 1 are neighbours iff their reduction windows are adjacent at l.
// Only pairs with a virtual end are stored; regular pairs are implicit in the array. Each
// virtual parent visits its sons' neighbours once, and a stamp per parent skips repeats, so no
// sorting is needed: a virtual-virtual pair is emitted by its smaller id, a virtual-regular
// pair by the virtual end.
void BipBuilder::IntraLevelEdges(int l) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  up.edges.clear();
  if (options_.link_across_kinds) DistantRegularEdges(l);
  if (up.num_virtual == 0) return;
  // The sons of each virtual parent, grouped (counting sort by parent). Only stages 2 and 3
  // give a vertex a virtual parent, so the linked sons are all there is to look at; those with
  // a virtual parent are gathered first, without a branch (the kind of parent is
  // unpredictable).
  const int first_virtual = up.num_cells();
  const int parents = up.num_ids();
  scratch_->virtual_sons_.resize(scratch_->linked_.size());
  int num_sons = 0;
  for (int id : scratch_->linked_) {
    scratch_->virtual_sons_[num_sons] = id;
    num_sons += cur.parent[id] >= first_virtual;
  }
  scratch_->son_offsets_.assign(up.num_virtual + 1, 0);
  for (int k = 0; k < num_sons; ++k) {
    ++scratch_->son_offsets_[cur.parent[scratch_->virtual_sons_[k]] - first_virtual + 1];
  }
  for (int v = 0; v < up.num_virtual; ++v) scratch_->son_offsets_[v + 1] += scratch_->son_offsets_[v];
  scratch_->sons_.resize(num_sons);
  scratch_->stamp_.assign(scratch_->son_offsets_.begin(), scratch_->son_offsets_.end() - 1);  // fill cursor
  for (int k = 0; k < num_sons; ++k) {
    const int id = scratch_->virtual_sons_[k];
    scratch_->sons_[scratch_->stamp_[cur.parent[id] - first_virtual]++] = id;
  }
  // scratch_->stamp_[q + 1] == p once p has seen parent q; slot 0 stands for "no parent" (q = -1).
  scratch_->stamp_.assign(parents + 1, -1);
  const int cols = cur.cols, rows = cur.rows;
  const int grid[8] = {-cols - 1, -cols, -cols + 1, -1, 1, cols - 1, cols, cols + 1};
  for (int p = first_virtual; p < parents; ++p) {
    // Marking "no parent" and p itself as seen leaves one test per neighbour.
    scratch_->stamp_[0] = p;
    scratch_->stamp_[p + 1] = p;
    auto visit = [&](int neighbour) {
      const int q = cur.parent[neighbour];
      const bool seen = scratch_->stamp_[q + 1] == p;
      scratch_->stamp_[q + 1] = p;
      if (!seen && (q < first_virtual || q > p)) up.edges.push_back(EdgeKey(p, q));
    };
    for (int k = scratch_->son_offsets_[p - first_virtual]; k < scratch_->son_offsets_[p - first_virtual + 1]; ++k) {
      const int son = scratch_->sons_[k];
      if (!cur.IsVirtual(son)) {
        const int row = son / cols, col = son - row * cols;
        if (row > 0 && col > 0 && row + 1 < rows && col + 1 < cols) {
          for (int d = 0; d < 8; ++d) visit(son + grid[d]);
        } else {
          for (int d = 0; d < 8; ++d) {
            const int x = col + kDx[d], y = row + kDy[d];
            if (x >= 0 && y >= 0 && x < cols && y < rows) visit(y * cols + x);
          }
        }
      }
      for (int e = AdjacencyBegin(son); e < AdjacencyEnd(son); ++e) visit(scratch_->adjacency_[e]);
    }
  }
}

int Bip::CountRoots() const {
  int roots = 0;
  for (int l = 0; l < num_levels_; ++l) {
    const BipLevel& level = (*levels_)[l];
    for (int id = 0; id < level.num_ids(); ++id) {
      if (level.Exists(id) && level.parent[id] < 0) ++roots;
    }
  }
  return roots;
}

int Bip::LabelRoots(cv::Mat* labels, std::vector<VertexRef>* root_refs) const {
  ATTEND_CHECK(levels_ != nullptr) << "labelling a released pyramid";
  struct ScratchLease {
    BipPool* pool;
    std::unique_ptr<BipScratch> scratch;
    ~ScratchLease() { pool->GiveScratch(std::move(scratch)); }
  } lease{pool_, pool_->TakeScratch()};
  // Top-down: a vertex takes its parent's root, or starts a new one.
  std::vector<int32_t>& above = lease.scratch->label_[0];
  std::vector<int32_t>& current = lease.scratch->label_[1];
  std::vector<VertexRef>& found = lease.scratch->roots_;
  found.clear();
  int roots = 0;
  for (int l = num_levels_ - 1; l >= 1; --l) {
    const BipLevel& level = (*levels_)[l];
    current.assign(level.num_ids(), -1);
    for (int id = 0; id < level.num_ids(); ++id) {
      if (!level.Exists(id)) continue;
      const int p = level.parent[id];
      if (p >= 0) {
        current[id] = above[p];
      } else {
        current[id] = roots++;
        if (root_refs != nullptr) found.push_back({l, id});
      }
    }
    std::swap(above, current);
  }
  // Level 0, whose ids are the pixels in raster order, in the same pass as numbering the roots
  // by first appearance, so that labels do not depend on the order in which levels were
  // visited.
  const BipLevel& base = (*levels_)[0];
  labels->create(height_, width_, CV_32SC1);
  std::vector<int32_t>& renumber = lease.scratch->label_[1];
  renumber.assign(roots + base.num_regular, -1);  // level 0 adds at most num_regular roots
  int next = 0;
  for (int row = 0; row < height_; ++row) {
    int32_t* out = labels->ptr<int32_t>(row);
    for (int col = 0, id = row * width_; col < width_; ++col, ++id) {
      if (base.hom[id] == 0) {
        out[col] = -1;
        continue;
      }
      const int p = base.parent[id];
      int root;
      if (p >= 0) {
        root = above[p];
      } else {
        root = roots++;
        if (root_refs != nullptr) found.push_back({0, id});
      }
      if (renumber[root] < 0) renumber[root] = next++;
      out[col] = renumber[root];
    }
  }
  if (root_refs != nullptr) {
    root_refs->assign(next, VertexRef{});
    for (int root = 0; root < roots; ++root) {
      if (renumber[root] >= 0) (*root_refs)[renumber[root]] = found[root];
    }
  }
  return next;
}

void Bip::AncestorMap(int level, cv::Mat* ids) const {
  ATTEND_CHECK(level >= 0 && level < num_levels_) << "level " << level << " out of range";
  ids->create(height_, width_, CV_32SC1);
  const BipLevel& base = (*levels_)[0];
  for (int row = 0; row < height_; ++row) {
    int32_t* out = ids->ptr<int32_t>(row);
    for (int col = 0; col < width_; ++col) {
      int id = row * width_ + col;
      if (base.hom[id] == 0) id = -1;
      for (int l = 0; l < level && id >= 0; ++l) id = (*levels_)[l].parent[id];
      out[col] = id;
    }
  }
}

cv::Mat Bip::ReceptiveField(int level, int id) const {
  cv::Mat ids;
  AncestorMap(level, &ids);
  cv::Mat field = ids == id;
  return field;
}

}  // namespace attend
