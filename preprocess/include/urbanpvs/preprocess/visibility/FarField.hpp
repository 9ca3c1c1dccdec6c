// SPDX-License-Identifier: GPL-3.0-or-later
// The far field of the hierarchical test (thesis 5.6): the objects that the cull maps around a
// cell leave open beyond the largest map, decided per sample by a front-to-back sweep over the
// occluder quadtree with the sample's horizon (SampleHorizon). An object is hidden from the cell
// when it is hidden from every sample: the thesis's min-over-samples merge (5.5), taken per
// object instead of per pixel. Nodes and occluders already hidden are skipped whole, whole
// districts of objects are tested at once (the object quadtree), and the sweep of a sample
// stops when every open object has been met. Pixel centres the horizon's sectors cannot decide
// are traced exactly (SightLine), so the far field never hides what the brute-force map shows.
// Occluders far from a sample enter its horizon by their far outlines (BakeScene::
// horizon_occluder: a polygon inside each, with fewer walls); a part of an occluder hides no
// more than the whole, and the sight lines keep every wall. Steep sloped tops (pitched roof
// faces) stay out of the horizons: what only they hide is left to the sight lines. The sweeps
// walk a quadtree of the occluders the horizons take, so those faces do not keep nodes open.
// The terrain's sloped squares come from a pyramid instead (TerrainPyramid): merged into
// coarser squares, which lie under them, as the sweep gets farther from them.
#pragma once

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/visibility/CellCounters.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

namespace urbanpvs::preprocess {

/// Per-thread scratch state for the far field of one scene; the scene must outlive it.
///
/// What one sample decides for one object (seen or hidden) depends on the two alone: the sweep
/// builds the horizon from the occluders in front-to-back order whichever objects are asked, and
/// objects are asked without changing it (SampleHorizon::hides_as_is). A sample on a cell edge
/// belongs to the two cells beside it, a corner sample to about six, and neighbouring cells leave
/// nearly the same objects to the far field; so the answers of the last samples swept are kept
/// and a cell asks a sample only what it has not answered yet. The PVS is the same whatever was
/// kept, so it stays the same on any thread and in any order of the cells.
class FarField {
 public:
  /// Which occluders the horizons take. The PVS is the same either way (a pixel centre the
  /// horizon leaves open is traced exactly past every occluder); the time is not: the walls of
  /// steep sloped tops (pitched roof faces) cost the sweeps more than tracing what only they hide
  /// (README, "Steep sloped tops stay out of the horizons").
  enum class HorizonTops { AllButSteep, All };

  /// How the horizons take the terrain's sloped squares: from the scene's TerrainPyramid,
  /// coarser with distance, or square by square (as other occluders, steep ones left out). The
  /// PVS is the same either way; on Andorra la Vella's slopes the pyramid took 2.6-2.8 times less
  /// time (README, "Terrain as an occluder").
  enum class TerrainHorizon { Pyramid, Squares };

  /// Where a sweep asked about few objects looks: only in their directions (the occluders in
  /// every other direction skipped), or all round as a sweep asked about every object does.
  /// The PVS is the same either way (SampleHorizon::watch_none says why); on the generated
  /// cities a quarter of the sweeps are such, and watching their objects alone adds 18-24 %
  /// fewer walls to the horizons (README, "Sweeps that watch their few objects").
  enum class SweepWatch { FewObjects, AllRound };

  /// Keeps the answers of up to `kept_samples` samples (0: none); fewer when one sample's
  /// answers (two bits per object of the city) would make them take more than kKeptBytes.
  explicit FarField(const BakeScene& scene, std::size_t kept_samples = kKeptSamples,
                    HorizonTops tops = HorizonTops::AllButSteep,
                    TerrainHorizon terrain = TerrainHorizon::Pyramid,
                    SweepWatch watch = SweepWatch::FewObjects);

  // About 400 cells' samples: a cell's neighbours across a fold of the Hilbert curve come
  // hundreds of cells later. With 256 (and threads that took chunks in turn), 15 % of the full
  // sweeps on the generated 1 km² city's centre were of samples swept before; with 8,192 and a
  // stretch per thread, 2 % (README, "Kept answers along stretches").
  static constexpr std::size_t kKeptSamples = 8192;
  static constexpr std::size_t kKeptBytes = std::size_t{32} << 20;

  /// Of the `open` objects, those not proven hidden from every one of `samples`, in the order
  /// they were found visible. With no occluder, no object tree or no sample, every open object
  /// (nothing proves one hidden). Counts objects_far_field, occluders_far_field, sight_lines,
  /// sample_sweeps and sweeps_spared.
  std::vector<std::uint32_t> visible(std::span<const Vec3> samples,
                                     std::span<const std::uint32_t> open, CellCounters& counters);
  /// As visible(), with every object of the city open but `decided` (distinct objects). The
  /// work per call does not grow with the objects left open, only with the words of a bit per
  /// object: a cell's small maps decide the few objects near it, and the rest are open.
  std::vector<std::uint32_t> visible_all_but(std::span<const Vec3> samples,
                                             std::span<const std::uint32_t> decided,
                                             CellCounters& counters);

 private:
  struct Event {  ///< the sweep's queue: a node, occluder or object at its distance
    double distance;
    std::uint32_t kind, id;
  };
  // Sets of objects are bits in the order of a depth-first walk of the object quadtree
  // (position_), so that the objects below any node are one run of bits (run_): whether a node
  // holds an object still asked is a scan of a few words, and a call's sets are word operations.
  using Bits = std::vector<std::uint64_t>;
  struct SampleAnswers {  ///< per object of the city: asked this sample, and if so seen from it
    Vec3 sample{};
    std::uint64_t last_used = 0;  ///< the visible() call that last read it (0: free)
    Bits asked, seen;
    std::uint32_t newer = 0, older = 0;  ///< neighbours in the list by last_used (kNoSlot)
  };
  /// A sample's coordinates bit for bit: samples are the mesh's own, shared by the cells of an
  /// edge exactly.
  struct SampleKey {
    std::uint64_t x, y, z;
    bool operator==(const SampleKey&) const = default;
  };
  struct SampleKeyHash {
    std::size_t operator()(const SampleKey& k) const noexcept;
  };
  static constexpr std::uint32_t kNoSlot = 0xffffffffu;
  static SampleKey key_of(const Vec3& s);
  /// Moves slot k to the newest end of the list.
  void touch(std::uint32_t k);
  struct Run {
    std::uint32_t begin = 0, end = 0;
  };
  /// The objects of open_ (less those already found) that `sample` sees, in the order found,
  /// asking those of ask_; they are added to `seen`.
  void sweep(const Vec3& sample, CellCounters& counters, std::vector<std::uint32_t>& seen);
  /// visible() for the objects of open_.
  std::vector<std::uint32_t> visible_open(std::span<const Vec3> samples, CellCounters& counters);
  bool any_asked(Run run) const;
  SampleAnswers* kept(const Vec3& sample);
  /// A slot for `sample`'s answers, none read by this call; nullptr when every slot is.
  SampleAnswers* keep(const Vec3& sample);

  const BakeScene& scene_;
  SampleHorizon horizon_;
  std::vector<Event> events_;
  std::vector<std::uint32_t> position_;   ///< per object: its bit in the sets
  std::vector<std::uint32_t> object_at_;  ///< per bit: its object
  std::vector<Run> run_;                  ///< per object-quadtree node: the bits below it
  // The occluders the horizons take, in a quadtree of their own: a node's box then holds only
  // them, so steep faces that stay out of the horizons neither widen nor raise it, and whole
  // nodes are found hidden sooner. Items index horizon_ids_, which names the scene's occluder.
  BoxQuadtree horizon_tree_;
  std::vector<std::uint32_t> horizon_ids_;
  const TerrainPyramid* terrain_ = nullptr;  ///< null: the squares are in horizon_tree_
  SweepWatch watch_;
  Bits open_, found_, ask_;  ///< this call's open objects, those found visible, a sweep's asked
  std::vector<std::uint32_t> seen_in_sweep_;  ///< valid where equal to sweep_stamp_
  std::uint32_t sweep_stamp_ = 0;
  std::vector<SampleAnswers> answers_;                                   ///< the kept samples
  std::unordered_map<SampleKey, std::uint32_t, SampleKeyHash> slot_of_;  ///< kept ones' slots
  std::uint32_t newest_ = kNoSlot, oldest_ = kNoSlot;  ///< ends of the list by last_used
  std::uint64_t calls_ = 0;
  std::vector<SampleAnswers*> known_;  ///< per sample of the current call: its kept answers
  std::vector<std::uint32_t> seen_;
  std::vector<std::size_t> order_;
};

}  // namespace urbanpvs::preprocess
