// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/RingCleanup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "RingRepair.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry {
namespace {

constexpr const char* kNonFinite = "coordinate is NaN or infinite";
constexpr const char* kZeroArea = "ring has zero area";

// Rings smaller than this (m²) cannot occlude anything and are almost always digitizing slips.
constexpr double kMinRingArea = 1e-6;

int orientation(Vec2 a, Vec2 b, Vec2 c) {
  const double v = cross(b - a, c - a);
  return (v > 0) - (v < 0);
}

bool on_segment(Vec2 p, Vec2 a, Vec2 b) {
  return std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= p.y &&
         p.y <= std::max(a.y, b.y);
}

// Closed-segment intersection (touching counts).
bool segments_meet(Vec2 p1, Vec2 p2, Vec2 q1, Vec2 q2) {
  const int o1 = orientation(p1, p2, q1), o2 = orientation(p1, p2, q2);
  const int o3 = orientation(q1, q2, p1), o4 = orientation(q1, q2, p2);
  if (o1 != o2 && o3 != o4 && o1 * o2 <= 0 && o3 * o4 <= 0) return true;
  if (o1 == 0 && on_segment(q1, p1, p2)) return true;
  if (o2 == 0 && on_segment(q2, p1, p2)) return true;
  if (o3 == 0 && on_segment(p1, q1, q2)) return true;
  if (o4 == 0 && on_segment(p2, q1, q2)) return true;
  return false;
}

std::string point_text(Vec2 p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", p.x, p.y);
  return buf;
}

struct Edge {
  Vec2 a, b;
  std::size_t ring, index, ring_size;
};

std::vector<Edge> edges_of(const Polygon& poly) {
  std::vector<Edge> edges;
  auto add = [&](const Ring& r, std::size_t ring) {
    for (std::size_t i = 0; i < r.size(); ++i)
      edges.push_back({r[i], r[(i + 1) % r.size()], ring, i, r.size()});
  };
  add(poly.outer, 0);
  for (std::size_t h = 0; h < poly.holes.size(); ++h) add(poly.holes[h], h + 1);
  return edges;
}

bool adjacent(const Edge& e, const Edge& f) {
  if (e.ring != f.ring) return false;
  const std::size_t n = e.ring_size;
  return (e.index + 1) % n == f.index || (f.index + 1) % n == e.index;
}

// Repairs in place what needs no judgement; returns a reason when the ring is beyond repair.
std::string repair_ring(Ring& r, bool outer, const RingContext& ctx, ReadReport& report) {
  for (Vec2 p : r)
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return kNonFinite;
  if (r.size() >= 2 && r.front() == r.back()) {
    r.pop_back();
  } else if (r.size() >= 3 && ctx.count_orientation) {
    // GeoJSON rings must repeat their first point; CityJSON rings never do (count_orientation
    // is off for those, so only GeoJSON counts here).
    ++report.repaired_unclosed;
  }
  Ring dedup;
  for (Vec2 p : r)
    if (dedup.empty() || !(dedup.back() == p)) dedup.push_back(p);
  while (dedup.size() > 1 && dedup.front() == dedup.back()) dedup.pop_back();
  report.repaired_duplicate_points += r.size() - dedup.size();
  r = std::move(dedup);
  if (r.size() < 3) return "ring has fewer than 3 distinct points";
  const double a2 = signed_area2(r);
  if (std::abs(a2) * 0.5 < kMinRingArea) return kZeroArea;
  if ((a2 > 0) != outer) {
    std::reverse(r.begin(), r.end());
    if (ctx.count_orientation) ++report.repaired_orientation;
  }
  return {};
}

}  // namespace

std::string polygon_defect(const Polygon& poly) {
  const std::vector<Edge> edges = edges_of(poly);
  const std::size_t n = edges.size();
  std::vector<Box2> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i].extend(edges[i].a);
    boxes[i].extend(edges[i].b);
  }
  // The defect of edges i < j, or "" (the message names edges[i]'s point).
  auto defect_of = [&](std::size_t i, std::size_t j) -> std::string {
    const Edge &e = edges[i], &f = edges[j];
    if (adjacent(e, f)) {
      // Neighbours share one vertex; they are defective only if they fold back onto each other.
      const bool e_first = (e.index + 1) % e.ring_size == f.index;
      const Edge& first = e_first ? e : f;
      const Edge& second = e_first ? f : e;
      const Vec2 p = first.a, shared = first.b, q = second.b;
      if (orientation(p, shared, q) == 0 && dot(p - shared, q - shared) > 0)
        return "ring folds back on itself at " + point_text(shared);
      return {};
    }
    if (segments_meet(e.a, e.b, f.a, f.b)) {
      const char* what =
          e.ring == f.ring ? "ring intersects itself near " : "rings intersect each other near ";
      return what + point_text(e.a);
    }
    return {};
  };
  // The pairs whose boxes overlap, by a sweep along x (a street region is one polygon of tens of
  // thousands of edges: all pairs took a tenth of Andorra's bake). Of the defective pairs, the
  // first in (i, j) order is reported, as a scan of all pairs in that order would report it.
  // (An edge with a NaN x overlaps nothing, as overlaps() says, and would break the order.)
  std::vector<std::uint32_t> by_x;
  by_x.reserve(n);
  for (std::size_t i = 0; i < n; ++i)
    if (!std::isnan(boxes[i].min.x) && !std::isnan(boxes[i].max.x))
      by_x.push_back(static_cast<std::uint32_t>(i));
  std::sort(by_x.begin(), by_x.end(), [&](std::uint32_t a, std::uint32_t b) {
    return boxes[a].min.x < boxes[b].min.x || (boxes[a].min.x == boxes[b].min.x && a < b);
  });
  std::size_t first_i = n, first_j = n;
  std::string first;
  for (std::size_t a = 0; a < by_x.size(); ++a) {
    const std::uint32_t k = by_x[a];
    for (std::size_t b = a + 1; b < by_x.size() && boxes[by_x[b]].min.x <= boxes[k].max.x; ++b) {
      const std::uint32_t m = by_x[b];
      if (!boxes[k].overlaps(boxes[m])) continue;
      const std::size_t i = std::min(k, m), j = std::max(k, m);
      if (i > first_i || (i == first_i && j >= first_j)) continue;
      if (std::string why = defect_of(i, j); !why.empty()) {
        first_i = i;
        first_j = j;
        first = std::move(why);
      }
    }
  }
  if (!first.empty()) return first;
  for (const Ring& h : poly.holes)
    if (!inside_ring(poly.outer, h.front())) return "hole lies outside the outer ring";
  return {};
}

std::vector<Polygon> clean_polygon(std::vector<Ring> rings, const RingContext& ctx,
                                   ReadReport& report) {
  auto fail = [&](const std::string& why) {
    throw InputError(InputProblem::InvalidGeometry, ctx.file, ctx.feature, why);
  };
  if (rings.empty()) fail("polygon has no ring");
  // Trivial repairs ring by ring; a ring left without area is dropped (an outer one takes the
  // polygon with it), which is a geometric repair.
  std::vector<std::string> defects;
  Polygon poly;
  bool outer_lost = false;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    std::string why = repair_ring(rings[i], i == 0, ctx, report);
    if (why == kNonFinite) fail(why);
    if (why == kZeroArea) {
      // Zero signed area: a bow-tie's lobes cancel, a spike folds flat. Kept for the winding
      // fill, which finds what area there is; named by what is wrong with it.
      const std::string defect = polygon_defect(Polygon{rings[i], {}});
      defects.push_back((i == 0 ? "outer ring: " : "hole " + std::to_string(i) + ": ") + why +
                        (defect.empty() ? "" : " (" + defect + ")"));
      (i == 0 ? poly.outer : poly.holes.emplace_back()) = std::move(rings[i]);
      continue;
    }
    if (!why.empty()) {
      defects.push_back((i == 0 ? "outer ring: " : "hole " + std::to_string(i) + ": ") + why);
      if (i == 0) outer_lost = true;
      continue;
    }
    (i == 0 ? poly.outer : poly.holes.emplace_back()) = std::move(rings[i]);
  }
  if (!outer_lost && defects.empty())
    if (std::string why = polygon_defect(poly); !why.empty()) defects.push_back(why);
  if (defects.empty()) return {std::move(poly)};
  std::string what;
  for (const std::string& d : defects) what += (what.empty() ? "" : "; ") + d;
  if (ctx.strict) fail(what + " (--strict refuses repairs)");
  std::vector<Polygon> pieces;
  if (!outer_lost) {
    std::vector<Ring> all{poly.outer};
    all.insert(all.end(), poly.holes.begin(), poly.holes.end());
    pieces = detail::fill_by_winding(all);
  }
  double before = outer_lost ? 0 : std::abs(signed_area2(poly.outer)) * 0.5, after = 0;
  for (const Ring& h : poly.holes) before -= std::abs(signed_area2(h)) * 0.5;
  for (const Polygon& p : pieces) after += area(p);
  char line[160];
  std::snprintf(line, sizeof line, " -> %zu simple piece%s, %.2f m2 (rings as given: %.2f m2)",
                pieces.size(), pieces.size() == 1 ? "" : "s", after, before);
  report.repairs.push_back(ctx.file + ": " + ctx.feature + ": " + what + line);
  return pieces;
}

}  // namespace urbanpvs::geometry
