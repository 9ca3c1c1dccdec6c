// SPDX-License-Identifier: GPL-3.0-or-later
// Kept in its own translation unit: CGAL's Boolean set operations with exact constructions take
// ~26 s and 1.4 GB to compile.
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_set_2.h>

#include <cmath>
#include <map>

namespace urbanpvs::geometry {
namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<K>;
using CgalPolygonWithHoles = CGAL::Polygon_with_holes_2<K>;

CgalPolygon to_cgal(const Ring& r) {
  CgalPolygon p;
  for (Vec2 v : r) p.push_back(K::Point_2(v.x, v.y));
  return p;
}

using ExactPoint = K::Point_2;
struct ExactLess {
  bool operator()(const ExactPoint& a, const ExactPoint& b) const {
    return CGAL::compare_xy(a, b) == CGAL::SMALLER;
  }
};
using Visits = std::map<ExactPoint, int, ExactLess>;

using Loop = std::vector<ExactPoint>;

// Splits a ring that visits a point more than once into loops that visit every point once.
// CGAL's Boolean operations return such "relatively simple" rings where a union only touches
// itself (two buildings meeting at a corner, a courtyard that meets the street at one point);
// the straight skeleton needs strictly simple rings.
std::vector<Loop> split_at_repeats(Loop ring) {
  std::vector<Loop> done, todo{std::move(ring)};
  while (!todo.empty()) {
    Loop r = std::move(todo.back());
    todo.pop_back();
    std::map<ExactPoint, std::size_t, ExactLess> first;
    std::size_t i = 0, j = 0;
    for (std::size_t k = 0; k < r.size() && j == 0; ++k) {
      auto [it, fresh] = first.emplace(r[k], k);
      if (!fresh) i = it->second, j = k;
    }
    if (j == 0) {
      done.push_back(std::move(r));
      continue;
    }
    Loop a(r.begin() + static_cast<std::ptrdiff_t>(i), r.begin() + static_cast<std::ptrdiff_t>(j));
    Loop b(r.begin() + static_cast<std::ptrdiff_t>(j), r.end());
    b.insert(b.end(), r.begin(), r.begin() + static_cast<std::ptrdiff_t>(i));
    todo.push_back(std::move(a));
    todo.push_back(std::move(b));
  }
  return done;
}

// Drops vertices on the straight line through their neighbours, decided exactly: the join keeps
// the endpoints of every shared wall, which would otherwise become tiny occluder edges.
// Points where the polygon touches itself are kept.
Loop simplified(Loop pts, const Visits& visits) {
  bool changed = true;
  while (changed && pts.size() > 3) {
    changed = false;
    for (std::size_t i = 0; i < pts.size() && pts.size() > 3; ++i) {
      const auto& a = pts[(i + pts.size() - 1) % pts.size()];
      const auto& b = pts[i];
      const auto& c = pts[(i + 1) % pts.size()];
      if (a == b || (visits.at(b) < 2 && CGAL::collinear(a, b, c))) {
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        --i;
      }
    }
  }
  return pts;
}

// Converts a loop to doubles, moving every point where loops touch a micrometre into the loop's
// own region along its corner's bisector. That only removes area, so the result stays a subset
// of the exact union (conservative), and touching loops come apart.
Ring to_ring(const Loop& pts, const Visits& visits) {
  constexpr double kPull = 1e-6;  // m
  const std::size_t n = pts.size();
  Ring r(n);
  for (std::size_t i = 0; i < n; ++i)
    r[i] = {CGAL::to_double(pts[i].x()), CGAL::to_double(pts[i].y())};
  Ring out = r;
  for (std::size_t i = 0; i < n; ++i) {
    if (visits.at(pts[i]) < 2) continue;
    const Vec2 in = r[i] - r[(i + n - 1) % n], next = r[(i + 1) % n] - r[i];
    const double li = std::hypot(in.x, in.y), lo = std::hypot(next.x, next.y);
    // Left normals point into the region for CCW outers and CW holes alike.
    Vec2 b{-in.y / li - next.y / lo, in.x / li + next.x / lo};
    double lb = std::hypot(b.x, b.y);
    if (lb < 1e-9) b = {-in.y / li, in.x / li}, lb = 1;
    out[i] = r[i] + (kPull / lb) * b;
  }
  return out;
}

bool counter_clockwise(const Loop& l) {
  K::FT a2 = 0;
  for (std::size_t i = 0; i < l.size(); ++i) {
    const auto& p = l[i];
    const auto& q = l[(i + 1) % l.size()];
    a2 += p.x() * q.y() - p.y() * q.x();
  }
  return a2 > 0;
}

// One CGAL polygon with holes -> strictly simple polygons with holes.
void append_from_cgal(const CgalPolygonWithHoles& p, std::vector<Polygon>& out) {
  Visits visits;
  auto count = [&](const CgalPolygon& ring) {
    for (const auto& v : ring.container()) ++visits[v];
  };
  count(p.outer_boundary());
  for (auto h = p.holes_begin(); h != p.holes_end(); ++h) count(*h);

  std::vector<Loop> loops = split_at_repeats(p.outer_boundary().container());
  for (auto h = p.holes_begin(); h != p.holes_end(); ++h)
    for (Loop& l : split_at_repeats(h->container())) loops.push_back(std::move(l));

  const std::size_t first = out.size();
  std::vector<Ring> holes;
  for (Loop& l : loops) {
    Loop s = simplified(std::move(l), visits);
    if (s.size() < 3) continue;
    (counter_clockwise(s) ? out.emplace_back().outer : holes.emplace_back()) = to_ring(s, visits);
  }
  for (Ring& h : holes) {
    const Vec2 probe = 0.5 * (h[0] + h[1]);  // on the hole's boundary, inside its outer ring
    for (std::size_t k = first; k < out.size(); ++k)
      if (inside_ring(out[k].outer, probe)) {
        out[k].holes.push_back(std::move(h));
        break;
      }
  }
}

CGAL::Polygon_set_2<K> polygon_set(const std::vector<Polygon>& polys) {
  std::vector<CgalPolygonWithHoles> in;
  in.reserve(polys.size());
  for (const Polygon& poly : polys) {
    CgalPolygonWithHoles p(to_cgal(poly.outer));
    for (const Ring& h : poly.holes) p.add_hole(to_cgal(h));
    in.push_back(std::move(p));
  }
  CGAL::Polygon_set_2<K> set;
  set.join(in.begin(), in.end());
  return set;
}

std::vector<Polygon> from_set(const CGAL::Polygon_set_2<K>& set) {
  std::vector<CgalPolygonWithHoles> result;
  set.polygons_with_holes(std::back_inserter(result));
  std::vector<Polygon> out;
  out.reserve(result.size());
  for (const CgalPolygonWithHoles& p : result) append_from_cgal(p, out);
  return out;
}

}  // namespace

std::vector<Polygon> union_polygons(const std::vector<Polygon>& polys) {
  return from_set(polygon_set(polys));
}

struct GrowingUnion::Exact {
  CGAL::Polygon_set_2<K> set;
};

GrowingUnion::GrowingUnion() : exact_(std::make_unique<Exact>()) {}
GrowingUnion::~GrowingUnion() = default;

void GrowingUnion::add(const std::vector<Polygon>& polys) {
  if (!polys.empty()) exact_->set.join(polygon_set(polys));
}

std::vector<Polygon> GrowingUnion::polygons() const {
  return from_set(exact_->set);
}

std::vector<Polygon> intersect_polygons(const std::vector<Polygon>& a,
                                        const std::vector<Polygon>& b) {
  if (a.empty() || b.empty()) return {};
  CGAL::Polygon_set_2<K> set = polygon_set(a);
  set.intersection(polygon_set(b));
  return from_set(set);
}

std::vector<Polygon> subtract_polygons(const std::vector<Polygon>& a,
                                       const std::vector<Polygon>& b) {
  if (a.empty() || b.empty()) return b.empty() && a.size() > 1 ? union_polygons(a) : a;
  CGAL::Polygon_set_2<K> set = polygon_set(a);
  set.difference(polygon_set(b));
  return from_set(set);
}

}  // namespace urbanpvs::geometry
