// The Bounded Irregular Pyramid (thesis chapter 3, SPEC 2.2).
//
// Each level l is a graph whose vertices are of two kinds. Regular vertices live in an
// incomplete 2-D array of (W >> l) x (H >> l) cells; a cell is a vertex iff Hom = 1, and two
// regular vertices are neighbours iff their cells are 8-adjacent. Virtual vertices form a
// simple graph with explicit edges. Vertices of one level share one id space: cells first
// (id = row * cols + col, holes included), then virtual vertices (id = cells + k). Every
// vertex has a feature vector (area-weighted mean of its sons'), an area in level-0 pixels and
// a parent id in the level above, or -1. A vertex without a parent is a root; its receptive
// field is one region of the segmentation.
//
// Level l + 1 is built from level l in four stages (SPEC 2.2): regular decimation; parent
// search then intra-level twining of regular orphans (raster order); virtual parent search then
// virtual linking of virtual orphans (union-find); intra-level edges of l + 1 from the
// adjacency of the sons at l. Building stops when a level would add no vertex.
#pragma once

#include <cstdint>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "pyramid/similarity.h"
#include "util/option_fields.h"

namespace attend {

struct BipOptions {
  // Variant (not in the thesis): an orphan also considers neighbours of the other kind, both
  // for parent search (a regular orphan takes a virtual neighbour's parent, a virtual orphan a
  // regular neighbour's) and for twining (a regular and a virtual orphan make a new virtual
  // vertex). It lets the regular and irregular parts of one homogeneous region meet, which the
  // faithful rules cannot do. It also connects two regular vertices whose reduction windows
  // touch although their cells are not array neighbours, which the thesis leaves implicit.
  // docs/PYRAMID.md measures it.
  bool link_across_kinds = false;
  // Safety bound on the number of levels; the stop rule ends far earlier in practice.
  int max_levels = 64;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h): link_across_kinds is the segmentation's key.
  static const OptionFields<BipOptions>& Fields();
};

// One level of the pyramid. Indexed by vertex id (see above).
struct BipLevel {
  int cols = 0;  // regular array width, W >> l
  int rows = 0;  // regular array height, H >> l
  int num_virtual = 0;
  int num_regular = 0;          // cells with Hom = 1
  std::vector<uint8_t> hom;     // per cell: 1 iff the cell is a regular vertex
  std::vector<float> feature;   // 3 per vertex
  std::vector<int32_t> area;    // per vertex, level-0 pixels (0 for holes)
  std::vector<int32_t> parent;  // per vertex, id in level l + 1, or -1
  // Explicit intra-level edges with at least one virtual end, as (min id, max id), each pair
  // once, in no particular order. Regular-regular adjacency is implicit in the array; with
  // BipOptions::link_across_kinds, regular pairs whose windows touch although their cells are
  // not array neighbours are stored too.
  std::vector<uint64_t> edges;

  int num_cells() const { return cols * rows; }
  int num_ids() const { return num_cells() + num_virtual; }
  bool IsVirtual(int id) const { return id >= num_cells(); }
  // Whether `id` is a vertex of this level (a Hom = 1 cell or a virtual vertex).
  bool Exists(int id) const { return IsVirtual(id) || hom[id] != 0; }
  const float* Feature(int id) const { return &feature[3 * static_cast<size_t>(id)]; }
  // Number of regular vertices (Hom = 1 cells).
  int CountRegular() const;
};

class BipPool;

// A built pyramid. Valid until the BipBuilder that made it builds again or is released.
class Bip {
 public:
  int width() const { return width_; }
  int height() const { return height_; }
  // Number of levels (the height of the hierarchy); level(0) is the base.
  int num_levels() const { return num_levels_; }
  const BipLevel& level(int l) const { return (*levels_)[l]; }
  // L_reg = floor(log2(min(width, height))).
  int top_regular_level() const { return top_regular_level_; }
  // The threshold used to link vertices of level l.
  float threshold(int l) const { return thresholds_[l]; }

  // Number of roots (regions).
  int CountRoots() const;

  // A vertex: its level and its id in that level.
  struct VertexRef {
    int level = 0;
    int id = 0;
  };

  // Labels every level-0 pixel with the index of its root (0..CountRoots()-1, roots numbered
  // in order of first appearance in raster order), -1 outside the mask. `labels` is CV_32SC1.
  // With `roots`, also gives the root vertex of each label. Returns the number of roots.
  int LabelRoots(cv::Mat* labels, std::vector<VertexRef>* roots = nullptr) const;

  // For every level-0 pixel, the id of its ancestor at `level` (itself at level 0), or -1 when
  // its chain ends below `level` or it is outside the mask. CV_32SC1.
  void AncestorMap(int level, cv::Mat* ids) const;

  // The receptive field of vertex `id` of `level`: a CV_8UC1 mask of its level-0 pixels.
  cv::Mat ReceptiveField(int level, int id) const;

 private:
  friend class BipBuilder;
  const std::vector<BipLevel>* levels_ = nullptr;
  BipPool* pool_ = nullptr;  // lends LabelRoots its scratch
  std::vector<float> thresholds_;
  int width_ = 0;
  int height_ = 0;
  int num_levels_ = 0;
  int top_regular_level_ = 0;
};

// The working buffers of a build (and of labelling its roots), needed only while it runs.
struct BipScratch;

// Buffers shared by the pyramids of a run (docs/PYRAMID.md, "Memory"). The pyramids of a frame
// (its segmentation, the trackers', the saliency segmentation) are built one after another, or
// two at a time with a second thread, so they need not each keep their own: a build borrows a
// scratch for as long as it runs, and a BipBuilder borrows the levels its pyramid lives in from
// its Build() until its Release(). Idle buffers are kept for the next build (so a stream of
// frames allocates nothing after the first), lent to the build they fit best, and the pool
// keeps only a few idle level sets. The run's pool is its ExecutionContext's
// (util/execution_context.h), handed to the builders. Thread-safe.
class BipPool {
 public:
  BipPool();
  ~BipPool();
  BipPool(const BipPool&) = delete;
  BipPool& operator=(const BipPool&) = delete;

  // A build over this many cells or more is large (above 362 x 362: 640x480 frames, not
  // 320x240 ones). One large scratch is lent at a time, a second large build waiting for it:
  // at 640x480 a scratch is 8.6 MB, and two threads that each build a frame's pyramid at once
  // (attend run with two threads, pipeline/frame_pipeline.h) would otherwise hold two.
  static constexpr size_t kLargeCells = size_t{1} << 17;

  // Idle buffers, in bytes of capacity (what the pool holds beyond what is lent out).
  size_t IdleBytes() const;
  // The idle scratches' part of it.
  size_t IdleScratchBytes() const;
  // The most scratches of large builds (kLargeCells) lent at once so far: 1 once any was.
  int MostLargeScratchesLent() const;
  // Idle scratches and level sets.
  int IdleScratches() const;
  int IdleLevelSets() const;
  // Frees the idle buffers.
  void Clear();

 private:
  friend class BipBuilder;
  friend class Bip;
  using Levels = std::vector<BipLevel>;
  // At most this many idle level sets are kept; a set given back beyond it is freed.
  static constexpr int kMaxIdleLevelSets = 6;

  // A scratch for a build or a labelling over `cells` cells; GiveScratch with the same count.
  std::unique_ptr<BipScratch> TakeScratch(size_t cells);
  void GiveScratch(std::unique_ptr<BipScratch> scratch, size_t cells);
  // A level set for a pyramid over `cells` pixels: the idle one that fits best.
  std::unique_ptr<Levels> TakeLevels(size_t cells);
  void GiveLevels(std::unique_ptr<Levels> levels);
  // The idle scratches' bytes, the large one's included; `mutex_` held.
  size_t IdleScratchBytesLocked() const;

  mutable std::mutex mutex_;
  std::condition_variable scratch_returned_;
  int large_lent_ = 0;       // large scratches lent out: 0 or 1
  int most_large_lent_ = 0;  // the most at once so far
  std::vector<std::unique_ptr<BipScratch>> idle_scratch_;  // those of small builds
  std::unique_ptr<BipScratch> large_idle_;  // the large builds' one, when idle
  std::vector<std::unique_ptr<Levels>> idle_levels_;
};

// Builds pyramids. Its buffers are borrowed from a BipPool: the scratch while a build runs,
// the levels from Build() until Release() (or the builder's end), so that builders used one
// after another share their memory and a stream of frames allocates nothing after the first.
class BipBuilder {
 public:
  // `pool`: the pool to borrow from, the caller's (a run's: its ExecutionContext's), which
  // must outlive the builder; nullptr: a pool of the builder's own, as a builder used alone
  // needs.
  explicit BipBuilder(BipOptions options = {}, BipPool* pool = nullptr);
  ~BipBuilder();
  BipBuilder(const BipBuilder&) = delete;
  BipBuilder& operator=(const BipBuilder&) = delete;

  // Builds the pyramid over `features` (CV_32FC3, level-0 vectors as made by the policy's
  // Features()). With a non-empty `mask` (CV_8UC1, same size) only pixels where it is
  // non-zero take part. The threshold schedule's top regular level is that of an image whose
  // smaller side is `schedule_side` (> 0), or the features' (0): a pyramid built over a part of
  // a larger masked image then links with that image's thresholds. The result refers to this
  // builder's buffers.
  const Bip& Build(const cv::Mat& features, const SimilarityPolicy& policy,
                   const cv::Mat& mask = cv::Mat(), int schedule_side = 0);

  // Gives the levels back to the pool: bip() is no longer valid (until the next Build()).
  void Release();

  const Bip& bip() const { return bip_; }
  const BipOptions& options() const { return options_; }

 private:
  void BuildLevel(int l, float threshold);
  void NeighbourDistances(int l);
  void RegularDecimation(int l, float t2);
  void RegularOrphans(int l, float t2);
  void VirtualOrphans(int l, float t2);
  void UpdateParents(int l);
  void IntraLevelEdges(int l);
  void DistantRegularEdges(int l);
  void BuildAdjacency(int l);
  int NewVirtual(BipLevel* up);
  void Link(int l, int id, int parented, float parented_d2, int orphan, float orphan_d2, float t2);
  // The range in adjacency_ of a vertex's explicit neighbours (empty when the level has none);
  // defined in pyramid/bip_internal.h.
  inline int AdjacencyBegin(int id) const;
  inline int AdjacencyEnd(int id) const;

  BipOptions options_;
  std::unique_ptr<BipPool> own_pool_;  // when the builder was given none
  BipPool* pool_;
  std::unique_ptr<std::vector<BipLevel>> levels_;  // borrowed from pool_, or null
  Bip bip_;
  BipScratch* scratch_ = nullptr;  // borrowed from pool_ while Build() runs
};

}  // namespace attend
