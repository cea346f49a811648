#include "pyramid/bip.h"

#include <algorithm>
#include <cmath>
#include <mutex>

#include "pyramid/bip_internal.h"
#include "util/error.h"
#include "util/vector_clones.h"

// The stages of building a level are in files of their own (pyramid/bip_internal.h names them);
// here are the options, the build level by level and the reading of a built pyramid.

namespace attend {

namespace {

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

}  // namespace

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

BipBuilder::BipBuilder(BipOptions options, BipPool* pool)
    : options_(options),
      own_pool_(pool == nullptr ? std::make_unique<BipPool>() : nullptr),
      pool_(pool != nullptr ? pool : own_pool_.get()) {
  const std::string problem = options_.Check();
  ATTEND_CHECK(problem.empty()) << problem;
  bip_.pool_ = pool_;
}

BipBuilder::~BipBuilder() { Release(); }

void BipBuilder::Release() {
  if (levels_ != nullptr) pool_->GiveLevels(std::move(levels_));
  bip_.levels_ = nullptr;
  bip_.num_levels_ = 0;
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
    size_t cells;
    std::unique_ptr<BipScratch> scratch;
    ~ScratchLease() {
      *held = nullptr;
      pool->GiveScratch(std::move(scratch), cells);
    }
  } lease{pool_, &scratch_, cells, pool_->TakeScratch(cells)};
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
  const size_t cells = static_cast<size_t>(width_) * height_;
  struct ScratchLease {
    BipPool* pool;
    size_t cells;
    std::unique_ptr<BipScratch> scratch;
    ~ScratchLease() { pool->GiveScratch(std::move(scratch), cells); }
  } lease{pool_, cells, pool_->TakeScratch(cells)};
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
