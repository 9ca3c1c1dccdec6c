// Shared fixtures and independent geometry checks for the city generator tests. The checks use
// exact integer millimetre arithmetic and deliberately share no code with the generator.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "urbanpvs/cities/CityGenerator.hpp"

namespace citytest {

using urbanpvs::cities::City;
using urbanpvs::cities::CityParams;
using urbanpvs::cities::Polygon;
using urbanpvs::cities::Ring;
using urbanpvs::cities::RoofMode;

/// Cities are generated once per test process and shared (generation is the slow part).
inline const City& city(double km2, std::uint64_t seed, RoofMode roofs) {
  struct Entry {
    double km2;
    std::uint64_t seed;
    RoofMode roofs;
    City city;
  };
  // unique_ptr: references handed out stay valid as the cache grows, and the cities are freed at
  // exit (LeakSanitizer runs in the sanitizer test configuration).
  static std::vector<std::unique_ptr<Entry>> cache;
  for (const auto& e : cache) {
    if (e->km2 == km2 && e->seed == seed && e->roofs == roofs) return e->city;
  }
  CityParams p;
  p.size_km2 = km2;
  p.seed = seed;
  p.roofs = roofs;
  cache.push_back(
      std::make_unique<Entry>(Entry{km2, seed, roofs, urbanpvs::cities::generateCity(p)}));
  return cache.back()->city;
}

inline const City& oneKm2Flat() {
  return city(1.0, 7, RoofMode::Flat);
}
inline const City& oneKm2Lod2() {
  return city(1.0, 7, RoofMode::Lod2);
}

struct P {
  std::int64_t x;
  std::int64_t y;
  bool operator==(const P&) const = default;
  auto operator<=>(const P&) const = default;
};

inline std::int64_t mm(double metres) {
  return std::llround(metres * 1000.0);
}
inline P toP(const urbanpvs::cities::Vec2& v) {
  return {mm(v.x), mm(v.y)};
}

inline std::vector<std::vector<P>> rings(const Polygon& poly) {
  std::vector<std::vector<P>> out;
  auto conv = [](const Ring& r) {
    std::vector<P> v;
    for (const auto& p : r) v.push_back(toP(p));
    return v;
  };
  out.push_back(conv(poly.outer));
  for (const Ring& h : poly.holes) out.push_back(conv(h));
  return out;
}

inline std::int64_t orient(P a, P b, P c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}
inline int sign(std::int64_t v) {
  return (v > 0) - (v < 0);
}

/// Twice the signed area (positive: counter-clockwise).
inline std::int64_t twiceArea(const std::vector<P>& r) {
  std::int64_t a = 0;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const P p = r[i];
    const P q = r[(i + 1) % r.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return a;
}

inline bool onSegment(P a, P b, P p) {
  return orient(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
         std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y);
}

/// Interiors cross at a single point (no touching, no collinear overlap).
inline bool properlyIntersect(P a, P b, P c, P d) {
  const int o1 = sign(orient(a, b, c));
  const int o2 = sign(orient(a, b, d));
  const int o3 = sign(orient(c, d, a));
  const int o4 = sign(orient(c, d, b));
  return o1 * o2 < 0 && o3 * o4 < 0;
}

/// Closed segments share at least one point.
inline bool segmentsTouch(P a, P b, P c, P d) {
  if (properlyIntersect(a, b, c, d)) return true;
  return onSegment(a, b, c) || onSegment(a, b, d) || onSegment(c, d, a) || onSegment(c, d, b);
}

/// Even-odd point-in-polygon for a point given in doubles (millimetres), all rings.
inline bool inside(const std::vector<std::vector<P>>& poly, double x, double y) {
  bool in = false;
  for (const auto& r : poly) {
    for (std::size_t i = 0, j = r.size() - 1; i < r.size(); j = i++) {
      const double xi = static_cast<double>(r[i].x), yi = static_cast<double>(r[i].y);
      const double xj = static_cast<double>(r[j].x), yj = static_cast<double>(r[j].y);
      if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi) in = !in;
    }
  }
  return in;
}

struct Box {
  std::int64_t x0, y0, x1, y1;
  bool overlaps(const Box& o) const { return x0 <= o.x1 && o.x0 <= x1 && y0 <= o.y1 && o.y0 <= y1; }
};

inline Box box(const std::vector<std::vector<P>>& poly) {
  Box b{poly[0][0].x, poly[0][0].y, poly[0][0].x, poly[0][0].y};
  for (const P& p : poly[0]) {
    b.x0 = std::min(b.x0, p.x);
    b.y0 = std::min(b.y0, p.y);
    b.x1 = std::max(b.x1, p.x);
    b.y1 = std::max(b.y1, p.y);
  }
  return b;
}

/// Every footprint that stands on the ground: simple buildings, and the parts of composite ones.
struct Shape {
  std::size_t building;
  std::vector<std::vector<P>> rings;
  Box bbox;
};

inline std::vector<Shape> groundShapes(const City& c) {
  std::vector<Shape> out;
  for (std::size_t i = 0; i < c.buildings.size(); ++i) {
    const auto& b = c.buildings[i];
    if (b.parts.empty()) {
      auto r = rings(b.footprint);
      out.push_back({i, r, box(r)});
    }
    for (const auto& part : b.parts) {
      auto r = rings(part.footprint);
      out.push_back({i, r, box(r)});
    }
  }
  return out;
}

}  // namespace citytest
