// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "urbanpvs/preprocess/visibility/AlsoForAvx2.hpp"
#include "urbanpvs/preprocess/visibility/DirectionAngle.hpp"

namespace urbanpvs::preprocess {
namespace {

constexpr double kSector = 2 * std::numbers::pi / SampleHorizon::kBins;
// Angles come from atan2 and differences of them: a few ulps off. Intervals a wall covers are
// narrowed, intervals a box covers widened by this much, so rounding never adds a sector.
constexpr double kAngleSlack = 1e-9;
constexpr std::uint32_t kNoMark = 0xffffffffu;  // a sector mark no sector carries

int bin_of(long long sector) {
  return static_cast<int>(((sector % SampleHorizon::kBins) + SampleHorizon::kBins) %
                          SampleHorizon::kBins);
}

Vec2 direction(double a) {
  return {std::cos(a), std::sin(a)};
}

// The directions of the sector borders, computed once, as two arrays twice round: the borders
// a wall crosses (less than half a turn) then lie in one run (border_crossings).
struct BorderTable {
  alignas(32) std::array<double, 2 * SampleHorizon::kBins> x, y;
};
const BorderTable kBorderTable = [] {
  BorderTable t;
  for (std::size_t k = 0; k < t.x.size(); ++k) {
    const Vec2 d = direction(static_cast<double>(k % SampleHorizon::kBins) * kSector);
    t.x[k] = d.x;
    t.y[k] = d.y;
  }
  return t;
}();

// Direction of the border where sector t begins.
Vec2 border(long long t) {
  const auto k = static_cast<std::size_t>(bin_of(t));
  return {kBorderTable.x[k], kBorderTable.y[k]};
}

double wrap_pi(double a) {
  while (a > std::numbers::pi) a -= 2 * std::numbers::pi;
  while (a <= -std::numbers::pi) a += 2 * std::numbers::pi;
  return a;
}

}  // namespace

SampleHorizon::SampleHorizon()
    : settled_(kBins),
      pending_(kBins),
      pending_count_(kBins),
      first_pending_(kBins, std::numeric_limits<double>::infinity()),
      reach_(kBins),
      near_(kBins),
      low_(kBins),
      sector_mark_(kBins, 0) {}

void SampleHorizon::reset(const Vec3& sample) {
  sample_ = sample;
  front_ = 0;
  std::fill(settled_.begin(), settled_.end(), Entry{0, -std::numeric_limits<double>::infinity()});
  std::fill(pending_count_.begin(), pending_count_.end(), std::uint8_t{0});
  std::fill(first_pending_.begin(), first_pending_.end(), std::numeric_limits<double>::infinity());
  watching_all_ = true;
}

double SampleHorizon::distance_to(const geometry::Box2& box) const {
  const double dx = std::max({0.0, box.min.x - sample_.x, sample_.x - box.max.x});
  const double dy = std::max({0.0, box.min.y - sample_.y, sample_.y - box.max.y});
  // The sample often lies within the box's x or y range (large quadtree nodes always nearly):
  // then the distance is exactly the other offset.
  if (dx == 0) return dy;
  if (dy == 0) return dx;
  return ground_length(dx, dy);
}

double SampleHorizon::slope_at(int bin, double distance) const {
  const auto b = static_cast<std::size_t>(bin);
  double slope =
      settled_[b].reach <= distance ? settled_[b].slope : -std::numeric_limits<double>::infinity();
  if (!(first_pending_[b] <= distance)) return slope;  // no pending wall reaches this near
  for (int k = 0; k < pending_count_[b]; ++k)
    if (pending_[b][static_cast<std::size_t>(k)].reach <= distance)
      slope = std::max(slope, pending_[b][static_cast<std::size_t>(k)].slope);
  return slope;
}

void SampleHorizon::settle(int bin, double distance) {
  auto& slots = pending_[static_cast<std::size_t>(bin)];
  std::uint8_t& n = pending_count_[static_cast<std::size_t>(bin)];
  Entry& settled = settled_[static_cast<std::size_t>(bin)];
  double first = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n;) {
    const Entry& p = slots[static_cast<std::size_t>(k)];
    if (p.reach <= distance) {
      if (p.slope > settled.slope) settled = p;
      slots[static_cast<std::size_t>(k)] = slots[static_cast<std::size_t>(--n)];
    } else {
      first = std::min(first, p.reach);
      ++k;
    }
  }
  first_pending_[static_cast<std::size_t>(bin)] = first;
}

void SampleHorizon::settle_sectors(long long first, long long last, double distance) {
  // Most sectors hold no pending wall, and a box near the sample spans hundreds of them: the
  // per-sector loop was most of hides()' time in `perf`. The counts are bytes, so eight empty
  // sectors are skipped with one load; settle() of an empty sector does nothing, so the result
  // is the same. A sector whose pending walls all reach farther than `distance` (a lower bound
  // of their reach is kept) is left alone too. The unwrapped range is at most kBins sectors: at
  // most two runs of bins.
  const std::uint8_t* const count = pending_count_.data();
  auto run = [&](std::size_t b, std::size_t end) {
    while (b < end) {
      if (b + 8 <= end) {
        std::uint64_t eight;
        std::memcpy(&eight, count + b, sizeof eight);
        if (eight == 0) {
          b += 8;
          continue;
        }
      }
      if (count[b] != 0 && first_pending_[b] <= distance) settle(static_cast<int>(b), distance);
      ++b;
    }
  };
  const auto b0 = static_cast<std::size_t>(bin_of(first));
  const auto n = static_cast<std::size_t>(last - first + 1);
  const std::size_t head = std::min(n, static_cast<std::size_t>(kBins) - b0);
  run(b0, b0 + head);
  run(0, n - head);
}

void SampleHorizon::insert(int bin, Entry e) {
  const auto b = static_cast<std::size_t>(bin);
  Entry& settled = settled_[b];
  // A wall that takes effect no sooner and hides no more than the settled one adds nothing.
  if (settled.reach <= e.reach && settled.slope >= e.slope) return;
  if (e.reach <= front_) {  // the sweep has passed it already
    if (e.slope > settled.slope) settled = e;
    return;
  }
  auto& slots = pending_[b];
  std::uint8_t& n = pending_count_[b];
  // Pending walls form a staircase: one that takes effect no sooner and hides no more than
  // another adds nothing, and the new one may make others redundant.
  for (int k = 0; k < n; ++k) {
    const Entry& p = slots[static_cast<std::size_t>(k)];
    if (p.reach <= e.reach && p.slope >= e.slope) return;
  }
  for (int k = 0; k < n;) {
    const Entry& p = slots[static_cast<std::size_t>(k)];
    if (p.reach >= e.reach && p.slope <= e.slope)
      slots[static_cast<std::size_t>(k)] = slots[static_cast<std::size_t>(--n)];
    else
      ++k;
  }
  if (n < kSlots) {
    slots[n++] = e;
    first_pending_[b] = std::min(first_pending_[b], e.reach);
    return;
  }
  // Full: fold into the entry that takes effect last. Both hold beyond the larger reach, so the
  // larger slope does too; the nearer one is only delayed (weaker, still conservative).
  Entry* last = &slots[0];
  for (Entry& p : slots)
    if (p.reach > last->reach) last = &p;
  last->reach = std::max(last->reach, e.reach);
  last->slope = std::max(last->slope, e.slope);
}

// The distances along borders first .. first + n - 1 (bins, first + n <= 2·kBins) at which
// they cross the line of a wall: num / cross(border, e), as close_sectors computes one, for a
// whole run of sectors at once (the divisions were most of a sweep's wall cost).
URBANPVS_ALSO_FOR_AVX2 void border_crossings(double num, Vec2 e, int first, int n, double* out) {
  const double* x = kBorderTable.x.data() + first;
  const double* y = kBorderTable.y.data() + first;
  for (int k = 0; k < n; ++k) out[k] = num / (x[k] * e.y - y[k] * e.x);
}

// Where the ray from the origin along `u` enters `box` (relative to the origin), or infinity.
double entry_along(const geometry::Box2& box, Vec2 u) {
  double t0, t1;
  return geometry::clip_line_to_box({0, 0}, u, box, std::numeric_limits<double>::infinity(), &t0,
                                    &t1)
             ? t0
             : std::numeric_limits<double>::infinity();
}

SampleHorizon::BoxView SampleHorizon::view(const geometry::Box3& box) const {
  BoxView v;
  v.distance = distance_to(box.xy);
  if (!(v.distance > 0)) return v;
  const Vec2 s{sample_.x, sample_.y};
  v.rel = {box.xy.min - s, box.xy.max - s};  // the box seen from the sample
  const geometry::Box2& rel = v.rel;
  // The box does not contain the sample, so seen from it the box spans less than π around the
  // direction to its centre.
  const Vec2 c = 0.5 * (rel.min + rel.max);
  const double base = direction_angle(c.y, c.x);
  v.lo = std::numeric_limits<double>::infinity();
  v.hi = -v.lo;
  auto bound = [&](Vec2 p) {
    const double a = direction_angle(geometry::cross(c, p), geometry::dot(c, p));
    v.lo = std::min(v.lo, a);
    v.hi = std::max(v.hi, a);
  };
  // Only silhouette corners bound the directions; the others lie strictly between them, so
  // their angles (two of the five atan2 calls per box) are not needed. Seen from outside both
  // of the box's ranges the silhouette is the two corners that pair the near x with the far y
  // and the far x with the near y; from within its y range (x range) it is the near column
  // (row), and a far corner on the sample's own line (coordinate exactly 0) ties with a near
  // one, so it is bounded too: the same angles as over all four corners.
  const bool x_apart = rel.min.x > 0 || rel.max.x < 0;
  const bool y_apart = rel.min.y > 0 || rel.max.y < 0;
  const double near_x = rel.min.x > 0 ? rel.min.x : rel.max.x;
  const double far_x = rel.min.x > 0 ? rel.max.x : rel.min.x;
  const double near_y = rel.min.y > 0 ? rel.min.y : rel.max.y;
  const double far_y = rel.min.y > 0 ? rel.max.y : rel.min.y;
  if (x_apart && y_apart) {
    bound({near_x, far_y});
    bound({far_x, near_y});
  } else if (x_apart) {
    bound({near_x, rel.min.y});
    bound({near_x, rel.max.y});
    if (rel.min.y == 0) bound({far_x, rel.min.y});
    if (rel.max.y == 0) bound({far_x, rel.max.y});
  } else {
    bound({rel.min.x, near_y});
    bound({rel.max.x, near_y});
    if (rel.min.x == 0) bound({rel.min.x, far_y});
    if (rel.max.x == 0) bound({rel.max.x, far_y});
  }
  // The farthest corner pairs the larger |x| with the larger |y|.
  v.reach = ground_length(std::max(-rel.min.x, rel.max.x), std::max(-rel.min.y, rel.max.y));
  v.lo += base - kAngleSlack;
  v.hi += base + kAngleSlack;
  v.first = static_cast<long long>(std::floor(v.lo / kSector));
  v.last = static_cast<long long>(std::floor(v.hi / kSector));
  v.rise = box.zmax - sample_.z;
  return v;
}

bool SampleHorizon::hides(const geometry::Box3& box) {
  const BoxView v = view(box);
  front_ = std::max(front_, v.distance);
  if (!(v.distance > 0) || v.last - v.first + 1 >= kBins) return false;
  settle_sectors(v.first, v.last, v.distance);
  return covers(v);
}

bool SampleHorizon::hides_as_is(const geometry::Box3& box) const {
  const BoxView v = view(box);
  if (!(v.distance > 0) || v.last - v.first + 1 >= kBins) return false;
  return covers(v);
}

bool SampleHorizon::covers(const BoxView& v) const {
  // The nearest point of the whole box, and whether a sector's wedge holds it.
  const Vec2 nearest{std::clamp(0.0, v.rel.min.x, v.rel.max.x),
                     std::clamp(0.0, v.rel.min.y, v.rel.max.y)};
  for (long long t = v.first; t <= v.last; ++t)
    if (watched(bin_of(t)) && !covers_sector(v, nearest, t)) return false;
  return true;
}

bool SampleHorizon::covers_sector(const BoxView& v, Vec2 nearest, long long t) const {
  const double d = v.distance, reach = v.reach, rise = v.rise;
  const int b = bin_of(t);
  // The walls passed at the box's nearest distance (settled there by hides(), or still
  // pending: slope_at counts both alike).
  const double passed = slope_at(b, d);
  if (rise > 0 ? passed * d > rise : passed * reach > rise) return true;  // hidden already
  // Else look closer: the nearest point of the box inside the sector's wedge is the box's
  // nearest point when the wedge holds it, else where one of the wedge's borders enters the
  // box; walls still pending up to that distance count too.
  const double a0 = std::max(v.lo, static_cast<double>(t) * kSector);
  const double a1 = std::min(v.hi, static_cast<double>(t + 1) * kSector);
  const Vec2 u0 = t == v.first ? direction(a0) : border(t);
  const Vec2 u1 = t == v.last ? direction(a1) : border(t + 1);
  double near = d;
  if (!(geometry::cross(u0, nearest) >= 0 && geometry::cross(nearest, u1) >= 0)) {
    near = std::min(entry_along(v.rel, u0), entry_along(v.rel, u1));
    near = std::isfinite(near) ? std::max(d, near * (1 - 1e-9)) : d;
  }
  // The steepest slope a point of the box's top shows in this sector: at its nearest distance
  // when the top is above the sample, at the farthest when below.
  const double needed = rise / (rise > 0 ? near : reach);
  return slope_at(b, near) > needed;
}

void SampleHorizon::watch_none() {
  watching_all_ = false;
  std::fill(watched_.begin(), watched_.end(), 0);
}

bool SampleHorizon::watch(const geometry::Box3& box) {
  const BoxView v = view(box);
  if (!(v.distance > 0) || v.last - v.first + 1 >= kBins) {
    watching_all_ = true;
    return false;
  }
  for (long long t = v.first; t <= v.last; ++t) {
    const auto b = static_cast<std::size_t>(bin_of(t));
    watched_[b >> 6] |= std::uint64_t{1} << (b & 63);
  }
  return true;
}

bool SampleHorizon::hides_point(Vec2 p, double top) const {
  const Vec2 v{p.x - sample_.x, p.y - sample_.y};
  const double dist = ground_length(v.x, v.y);
  if (!(dist > 0)) return false;
  const double a = direction_angle(v.y, v.x);
  // A point on a sector border belongs to both sectors: test both.
  for (double slack : {-kAngleSlack, kAngleSlack}) {
    const int b = bin_of(static_cast<long long>(std::floor((a + slack) / kSector)));
    if (!(slope_at(b, dist) * dist > top - sample_.z)) return false;
  }
  return true;
}

void SampleHorizon::add(const geometry::Occluder& occluder) {
  add_ring(occluder.shape.outer, occluder, false);
  // A hole's walls count only from a sample inside it (add_ring); a sample outside the hole's
  // bounds is not, and the hole's vertex directions (one atan2 each) need not be computed to
  // find that out. Courtyards are most holes, and most samples see them from outside.
  const Vec2 s{sample_.x, sample_.y};
  for (const geometry::Ring& h : occluder.shape.holes)
    if (geometry::bounds(h).overlaps({s, s})) add_ring(h, occluder, true);
}

// Closes sectors t0..t1 (unwrapped numbers) with the facing walls among edges k0..k1 of `ring`
// (indices mod n; angle(k) is vertex k's unwrapped direction). Each sector gets the farthest
// distance at which one of those walls crosses it: convex in the direction over a wall, so the
// largest value over a sector's part of a wall lies at one of the part's ends. Under a sloped
// top (thesis 4.2.1) the sector also takes the lowest point of those walls' tops within it, at
// an end of each part (the top is linear along a wall): a ray crosses a wall no lower than that
// and no farther than the reach, so the slope (lowest − eye) / reach stays below every ray's,
// and a sector whose lowest top is not above the eye gets nothing from that bound.
// Below the eye, a wall hides what a ray passes it below its top just as well (the ray enters the
// occluder; thesis 4.2.1), but (lowest − eye) is negative there and a ray's slope is least where
// it crosses nearest: the sector takes the nearest crossing within it, which is an end of a part
// of a wall, or the foot of the perpendicular from the sample when it lies between the ends
// (the distance along a wall falls towards that foot and rises beyond it). Looking down from a
// hillside onto the roofs below, those walls decide what the sight lines had to.
// Sectors marked with `skip_mark` are left alone; closed ones are marked with `mark`.
template <class Angle>
void SampleHorizon::close_sectors(const geometry::Ring& ring, std::size_t k0, std::size_t k1,
                                  Angle&& angle, long long t0, long long t1,
                                  const geometry::Occluder& occluder, std::uint32_t skip_mark,
                                  std::uint32_t mark) {
  const std::size_t n = ring.size();
  const Vec2 s{sample_.x, sample_.y};
  const bool sloped = occluder.sloped();
  // Nearest crossings are needed only where a top lies below the eye.
  const bool below = occluder.top_low() < sample_.z;
  touched_.clear();
  for (std::size_t k = k0; k <= k1; ++k) {
    const Vec2 p = ring[k % n], q = ring[(k + 1) % n];
    if (!faces(p, q, sample_)) continue;
    const Vec2 e = q - p;
    const double num = geometry::cross(p - s, e);
    auto along = [&](Vec2 u) { return num / geometry::cross(u, e); };
    // The wall's ends: where the rays towards them cross it is the ends themselves, so their
    // distances need no direction (cos, sin) and no division.
    const double a_p = angle(k), a_q = angle(k + 1);
    const bool p_first = a_p <= a_q;
    const double a_lo = p_first ? a_p : a_q;
    const double a_hi = p_first ? a_q : a_p;
    const double at_lo = vertex_distance_[(p_first ? k : k + 1) % n];
    const double at_hi = vertex_distance_[(p_first ? k + 1 : k) % n];
    // Along the wall's line the distance from the sample is least at the foot of the
    // perpendicular. A ray whose direction has a positive component along e crosses the line
    // past the foot (towards q), a negative one before it: the foot lies between two crossings
    // whose directions have components of opposite signs along e.
    const double foot = below ? std::abs(num) / ground_length(e.x, e.y) : 0;
    const auto u0 = std::max(t0, static_cast<long long>(std::floor(a_lo / kSector)));
    const auto u1 = std::min(t1, static_cast<long long>(std::floor(a_hi / kSector)));
    if (u1 < u0) continue;
    // Sector t spans [from, to] of this wall; `to` of one sector is `from` of the next.
    double at_from = static_cast<double>(u0) * kSector < a_lo ? at_lo : along(border(u0));
    // A sloped top along the wall: at its ends, and where a border crosses it.
    const double top_lo = sloped ? occluder.top_at(p_first ? p : q) : 0;
    const double top_hi = sloped ? occluder.top_at(p_first ? q : p) : 0;
    double top_from = !sloped || static_cast<double>(u0) * kSector < a_lo
                          ? top_lo
                          : occluder.top_at(s + at_from * border(u0));
    double along_from = 0;  // the direction of the crossing at `from`, along e
    if (below)
      along_from = geometry::dot(
          static_cast<double>(u0) * kSector < a_lo ? (p_first ? p : q) - s : border(u0), e);
    auto b = static_cast<std::size_t>(bin_of(u0));
    // The borders u0 + 1 .. u1 + 1, all at once.
    const int first = bin_of(u0 + 1);
    const auto n_borders = static_cast<int>(u1 - u0 + 1);
    crossing_.resize(static_cast<std::size_t>(n_borders));
    if (first + n_borders <= 2 * kBins) {
      border_crossings(num, e, first, n_borders, crossing_.data());
    } else {  // a wall faces the sample over less than half a turn: never
      for (int i = 0; i < n_borders; ++i)
        crossing_[static_cast<std::size_t>(i)] = along(border(u0 + 1 + i));
    }
    for (long long t = u0; t <= u1; ++t) {
      const bool at_end = static_cast<double>(t + 1) * kSector > a_hi;
      const double at_to = at_end ? at_hi : crossing_[static_cast<std::size_t>(t - u0)];
      // The wall's lowest point within the sector: its top is linear along the wall.
      double top_to = 0, low = 0;
      if (sloped) {
        top_to = at_end ? top_hi : occluder.top_at(s + at_to * border(t + 1));
        low = std::min(top_from, top_to);
      }
      double near = 0, along_to = 0;
      if (below) {
        along_to = geometry::dot(at_end ? (p_first ? q : p) - s : border(t + 1), e);
        near = (along_from < 0 && along_to > 0) || (along_from > 0 && along_to < 0)
                   ? foot
                   : std::min(at_from, at_to);
      }
      if (sector_mark_[b] != skip_mark) {
        if (reach_[b] == 0) {
          touched_.push_back(static_cast<int>(b));
          if (sloped) low_[b] = low;
          if (below) near_[b] = near;
        }
        reach_[b] = std::max({reach_[b], at_from, at_to, 1e-300});
        if (sloped) low_[b] = std::min(low_[b], low);
        if (below) near_[b] = std::min(near_[b], near);
      }
      at_from = at_to;
      top_from = top_to;
      along_from = along_to;
      b = b + 1 == static_cast<std::size_t>(kBins) ? 0 : b + 1;
    }
  }
  for (int b : touched_) {
    const auto i = static_cast<std::size_t>(b);
    // Slightly farther than computed: the divisions and square roots above are a few ulps
    // off.
    const double r = reach_[i] * (1 + 1e-9) + 1e-9;
    // A crossing's top comes from a computed point a few ulps off the wall: 0.1 µm lower.
    const double rise = (sloped ? low_[i] - 1e-7 : occluder.top_z) - sample_.z;
    reach_[i] = 0;
    sector_mark_[i] = mark;
    if (rise > 0) {
      insert(b, Entry{r, rise / r});
    } else if (rise < 0 && below) {
      // Slightly nearer than computed, for the same reason: the slope comes out no higher.
      const double nearest = near_[i] * (1 - 1e-9) - 1e-9;
      if (nearest > 0) insert(b, Entry{r, rise / nearest});
    }
  }
}

// The sectors a run of facing walls over the unwrapped directions [lo, hi] closes, as t0..t1;
// false when none: those wholly inside [lo, hi]. A run once around the sample (`around`: a
// courtyard whose every wall faces it) closes every sector, the seam's too, and there the
// sector holding the direction of the run's first vertex is crossed by the first wall at one end
// of [lo, hi] and by the last wall at the other, a turn apart. Both parts must count: behind a
// wall only what lies below its shadow plane is hidden (thesis 4.2.1), so a sector may claim a
// wall only from the farthest crossing over all of its rays (the horizon of thesis 5.6, per
// sector); one part alone would claim the nearer wall for rays that cross the farther one. So
// a full run takes every sector any of its walls crosses, floor(lo) to floor(hi), the seam's
// bin at both ends, and close_sectors keeps the farthest crossing per bin.
bool inner_sectors(double lo, double hi, bool around, long long* t0, long long* t1) {
  if (around || hi - lo >= 2 * std::numbers::pi) {
    *t0 = static_cast<long long>(std::floor(lo / kSector));
    *t1 = static_cast<long long>(std::floor(hi / kSector));
    return true;
  }
  *t0 = static_cast<long long>(std::ceil((lo + kAngleSlack) / kSector));
  *t1 = static_cast<long long>(std::floor((hi - kAngleSlack) / kSector)) - 1;
  return *t1 >= *t0;
}

// A ring closes sectors in two ways (thesis 4.2.1: each wall the sight line crosses hides what
// lies below its shadow plane):
//  - a run of consecutive walls facing the sample turns one way around it, so the walls' angular
//    intervals tile the run's interval: every ray in it crosses exactly one of them, and a
//    sector inside it is closed from the farthest of those crossings, seams between the walls
//    included (one wall alone would leave the sector at each corner open);
//  - every ray from a sample outside the ring into the ring's whole angular extent crosses the
//    ring, first entering it through some facing wall: sectors that no run closes (at concave
//    corners, where runs meet) are closed from the farthest facing wall crossing them. Taken
//    for every sector this would be loose where a ray leaves and re-enters a concave block.
// A sample inside a ring (a courtyard: inside a hole) sees every ray leave through a facing wall
// of the hole: one run around it.
void SampleHorizon::add_ring(const geometry::Ring& ring, const geometry::Occluder& occluder,
                             bool hole) {
  const std::size_t n = ring.size();
  if (n < 3) return;
  const Vec2 s{sample_.x, sample_.y};
  // Vertex directions, unwrapped along the ring: angle_[k] for vertex k, angle_[n] = back at 0.
  angle_.resize(n + 1);
  vertex_distance_.resize(n);
  const Vec2 v0 = ring[0] - s;
  angle_[0] = direction_angle(v0.y, v0.x);
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 a = ring[k] - s, b = ring[(k + 1) % n] - s;
    angle_[k + 1] =
        angle_[k] + wrap_pi(direction_angle(geometry::cross(a, b), geometry::dot(a, b)));
    vertex_distance_[k] = ground_length(a.x, a.y);
  }
  const double turn = angle_[n] - angle_[0];
  const bool around = std::abs(turn) > std::numbers::pi;  // winds around s
  if (around != hole)
    return;  // inside an outer ring is inside the occluder; outside a hole,
             // the hole's walls lie behind the outer ring's
  auto angle = [&](std::size_t k) { return k <= n ? angle_[k] : angle_[k - n] + turn; };
  auto facing = [&](std::size_t k) { return faces(ring[k % n], ring[(k + 1) % n], sample_); };

  if (++mark_ == kNoMark) {
    std::fill(sector_mark_.begin(), sector_mark_.end(), 0u);
    mark_ = 1;
  }
  const std::uint32_t by_run = mark_;
  // Runs, from the first edge that starts one (all edges when every wall faces the sample).
  std::size_t start = n;
  for (std::size_t k = 0; k < n && start == n; ++k)
    if (facing(k) && !facing(k + n - 1)) start = k;
  if (start == n) start = 0;
  int runs = 0;
  for (std::size_t k = start; k < start + n;) {
    if (!facing(k)) {
      ++k;
      continue;
    }
    const std::size_t first = k;
    while (k < start + n && facing(k)) ++k;
    ++runs;
    const double a = angle(first), b = angle(k);
    // Every wall faces the sample and the ring winds around it: the run tiles the full circle
    // (its angle is monotone along the ring), whatever rounding makes of |b - a| - 2π.
    const bool full = around && k - first == n;
    long long t0, t1;
    if (inner_sectors(std::min(a, b), std::max(a, b), full, &t0, &t1))
      close_sectors(ring, first, k - 1, angle, t0, t1, occluder, kNoMark, by_run);
  }
  // The run around the sample closed everything; a single run spans the ring's whole extent.
  if (around || runs <= 1) return;
  const auto [lo, hi] = std::minmax_element(angle_.begin(), angle_.end());
  long long t0, t1;
  if (inner_sectors(*lo, *hi, false, &t0, &t1))
    close_sectors(ring, 0, n - 1, angle, t0, t1, occluder, by_run, by_run);
}

}  // namespace urbanpvs::preprocess
