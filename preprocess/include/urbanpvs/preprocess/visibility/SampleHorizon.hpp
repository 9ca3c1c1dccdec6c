// SPDX-License-Identifier: GPL-3.0-or-later
// The occlusion horizon of one sample point, in polar form: for every direction around the
// sample (kBins sectors of the full circle), the steepest slope below which everything is hidden
// beyond the walls met so far. It is the cull map's horizon of thesis 5.6 taken per sample
// instead of after the merge: an object is hidden from the whole cell exactly when it is hidden
// from every sample (the merge is a min over samples, thesis 5.5), and per sample the umbra of
// 2.5D occluders is a function of direction and distance alone (the height along a ray from the
// sample rises linearly behind each wall it crosses, thesis 4.2.1). That makes it cheap far from
// the cell, where a cull map would need millions of pixels per sample.
//
// Conservative by construction, for the same ε-shrunk occluders as the cull maps:
//  - a sector counts a wall only when the facing walls of one ring cover the whole sector, and
//    only from the distance where every ray of the sector has crossed one of them;
//  - the slope of a sector is the least over its rays: the ray that crosses farthest where the
//    walls rise above the sample, nearest where they stand below it (looking down a hillside);
//  - a box is tested over every sector it touches, in each at its nearest point there, counting
//    only walls the sector's rays have crossed by then.
// So whatever it hides is hidden in the exact per-sample umbra, and so in the brute-force cull
// map, which samples that umbra at pixel centres, for every centre the box holds.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/preprocess/visibility/OccluderShadow.hpp"

namespace urbanpvs::preprocess {

/// The length of (dx, dy) on the ground, as the sweeps measure it: the square root of the sum of
/// squares. std::hypot also guards against overflow and underflow, which offsets in a city's
/// local frame (metres, far below 1e150 and above 1e-150 or exactly 0) never reach, and it was
/// 5-8 % of a sweep's time in `perf`. Both are within about an ulp of the true length; the
/// horizons' margins (1e-9 relative) are far wider.
inline double ground_length(double dx, double dy) {
  return std::sqrt(dx * dx + dy * dy);
}

class SampleHorizon {
 public:
  /// Sectors of the full circle: 2π/1024 ≈ 0.35°, 1.8 m at 300 m. The count changes no PVS (a
  /// pixel centre a sector leaves open gets its exact sight line) and trades the walls' cost, a
  /// wall is closed over every sector it spans, against sight lines; 1,024 measured fastest
  /// (README, "The far-field sector count").
  static constexpr int kBins = 1024;

  SampleHorizon();
  /// Starts over for `sample`: nothing hidden anywhere.
  void reset(const Vec3& sample);
  const Vec3& sample() const { return sample_; }

  /// Ground distance from the sample to `box` (0 when the sample lies in it).
  double distance_to(const geometry::Box2& box) const;

  /// True when everything in `box` up to box.zmax is hidden from the sample by the walls added
  /// so far that it lies behind. Meant for a front-to-back sweep (queries in order of
  /// distance_to, walls added as the sweep reaches them): then it misses no wall in front of the
  /// box. Any order stays conservative: a wall only counts from the distance where it has cut
  /// every ray of its sector.
  bool hides(const geometry::Box3& box);

  /// The answer hides() would give, without moving the sweep's front or settling a wall: the
  /// horizon stays exactly what its wall queries and add() made it. The far field asks this of
  /// objects, so that what a sample decides for an object depends on the sample and the object
  /// alone, never on which other objects were asked before (FarField reuses it across cells).
  bool hides_as_is(const geometry::Box3& box) const;

  /// Narrows what hides() and hides_as_is() are asked about, until reset(), to the sectors of
  /// the boxes then passed to watch(): a box counts as hidden when it is hidden in each watched
  /// sector it spans, and one that spans none of them counts as hidden outright. For a sweep
  /// that decides a few objects: it skips the occluders in every other direction. What it then
  /// says of a box within the watched sectors is what it says when every sector is watched,
  /// since the occluders it skips put no wall into those sectors, and those it keeps put the same
  /// walls there (a node of occluders skipped as hidden in them adds nothing there either: its
  /// walls lie behind the walls that hid it).
  void watch_none();
  /// Watches the sectors `box` spans. False, and every sector watched again, when it has none
  /// (the sample in it, or a box all round).
  bool watch(const geometry::Box3& box);

  /// True when the point `p` at height `top` is hidden by the walls added so far. For
  /// deciding objects the way a cull map does, by the pixel centres their box touches (thesis 7.2),
  /// where the box as a whole is not hidden.
  bool hides_point(Vec2 p, double top) const;

  /// Adds the walls of `occluder` that face the sample, above or below its eye. Call it once
  /// the sweep has reached the occluder (distance_to(occluder.bounds) >= the last query's).
  void add(const geometry::Occluder& occluder);

 private:
  struct Entry {
    double reach;  ///< from this distance on every ray of the sector has crossed the walls
    double slope;  ///< and everything below sample.z + slope·distance is hidden
  };
  static constexpr int kSlots = 8;
  struct BoxView {                  ///< a box as the sample sees it
    double distance = 0;            ///< to its nearest point (0: the sample is in it)
    double reach = 0;               ///< to its farthest corner
    double lo = 0, hi = 0;          ///< its directions (unwrapped, widened by the angle slack)
    long long first = 0, last = 0;  ///< the sectors they touch
    double rise = 0;                ///< of its top above the sample
    geometry::Box2 rel;             ///< the box relative to the sample
  };
  BoxView view(const geometry::Box3& box) const;
  bool covers(const BoxView& v) const;  ///< hides(), given the walls passed as they stand
  /// covers() in sector t alone; `nearest`: the box's nearest point, relative to the sample.
  bool covers_sector(const BoxView& v, Vec2 nearest, long long t) const;
  bool watched(int bin) const {
    const auto b = static_cast<std::size_t>(bin);
    return watching_all_ || ((watched_[b >> 6] >> (b & 63)) & 1u) != 0;
  }

  void add_ring(const geometry::Ring& ring, const geometry::Occluder& occluder, bool hole);
  template <class Angle>
  void close_sectors(const geometry::Ring& ring, std::size_t k0, std::size_t k1, Angle&& angle,
                     long long t0, long long t1, const geometry::Occluder& occluder,
                     std::uint32_t skip_mark, std::uint32_t mark);
  void insert(int bin, Entry e);
  void settle(int bin, double distance);
  /// settle() over the unwrapped sectors first..last (fewer than kBins of them).
  void settle_sectors(long long first, long long last, double distance);
  double slope_at(int bin, double distance) const;  ///< of the walls passed at `distance`

  Vec3 sample_;
  double front_ = 0;            ///< farthest query so far: walls passed there settle
  std::vector<Entry> settled_;  ///< per sector: the steepest passed wall (-infinity: none)
  std::vector<std::array<Entry, kSlots>> pending_;  ///< per sector: walls not yet passed
  std::vector<std::uint8_t> pending_count_;
  /// per sector: no pending wall reaches nearer (a lower bound: walls dropped or folded leave it)
  std::vector<double> first_pending_;
  bool watching_all_ = true;
  std::array<std::uint64_t, kBins / 64> watched_{};  ///< sectors watched (watch())
  std::vector<double> angle_, reach_;    ///< scratch of add_ring (reach_ per sector, kept 0)
  std::vector<double> near_;             ///< scratch of add_ring: per sector, nearest crossing
  std::vector<double> low_;              ///< scratch of add_ring: per sector, its lowest wall end
  std::vector<double> vertex_distance_;  ///< scratch of add_ring: each ring vertex's distance
  std::vector<double> crossing_;         ///< scratch of close_sectors: a wall's border crossings
  std::vector<int> touched_;
  std::vector<std::uint32_t> sector_mark_;  ///< sectors a run of the current ring closed
  std::uint32_t mark_ = 0;
};

}  // namespace urbanpvs::preprocess
