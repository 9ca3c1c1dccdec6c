// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/TerrainOccluders.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "LatticeMask.hpp"
#include "urbanpvs/geometry/city/ConvexClip.hpp"

namespace urbanpvs::geometry {
namespace {

// 4M squares (32 MB of heights): a 4 km city at the default 4 m, a larger one on coarser ones.
constexpr double kMaxSquares = 4.0e6;
// A tile holds about this much ground: a cell's map (32 pixels of 1.4 m: 45 m) meets one to
// four of them, and clips only their edges.
constexpr double kTileSide = 128;  // [Units: m]
// A square counts as covered when the TIN's pieces in it fill this share of it: what is left
// is the rounding of the clipped areas.
constexpr double kCovered = 1 - 1e-9;

struct Point3 {
  double x, y, z;
};

/// A triangle clipped by four half-planes has at most 7 corners.
struct ClipPolygon {
  std::array<Point3, 8> p{};
  int n = 0;
  std::size_t size() const { return static_cast<std::size_t>(n); }
  const Point3& operator[](std::size_t k) const { return p[k]; }
  void push_back(const Point3& q) { p[static_cast<std::size_t>(n++)] = q; }
};

// Keeps the part where `d(p) >= 0` (d affine in x, y), the height interpolated along each cut
// edge, so every corner of the result lies on the triangle.
template <class Distance>
ClipPolygon clip(const ClipPolygon& in, Distance d) {
  ClipPolygon out;
  geometry::clip_convex(in, out, d, [](const Point3& a, const Point3& b, double da, double db) {
    const double t = da / (da - db);
    return Point3{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
  });
  return out;
}

ClipPolygon clip_to_box(const Triangle3& t, const Box2& box) {
  ClipPolygon p;
  for (const Vec3& v : t.v) p.push_back({v.x, v.y, v.z});
  p = clip(p, [&](const Point3& q) { return q.x - box.min.x; });
  p = clip(p, [&](const Point3& q) { return box.max.x - q.x; });
  p = clip(p, [&](const Point3& q) { return q.y - box.min.y; });
  return clip(p, [&](const Point3& q) { return box.max.y - q.y; });
}

double area_of(const ClipPolygon& p) {
  double a = 0;
  for (int k = 0; k < p.n; ++k) {
    const Point3& u = p.p[static_cast<std::size_t>(k)];
    const Point3& v = p.p[static_cast<std::size_t>((k + 1) % p.n)];
    a += u.x * v.y - u.y * v.x;
  }
  return 0.5 * std::abs(a);
}

/// A grid of sub-cells over one tile: each square split into three columns and three rows at
/// ε from its sides. The erosion of a union of squares by a square of half-side ε < side / 2
/// is a union of such sub-cells: a point's ε-box meets a neighbour square only within ε of
/// the side they share.
class TileMask {
 public:
  TileMask(const TerrainRaster& r, int i0, int i1, int j0, int j1, double epsilon)
      : raster_(r),
        i0_(i0),
        j0_(j0),
        mask_(lines(r.area.min.x, i0, i1, r.square, epsilon),
              lines(r.area.min.y, j0, j1, r.square, epsilon)) {}

  /// The sub-cells of the squares at least h, eroded; true when any is set.
  bool erode(double h) {
    auto square = [&](int i, int j) { return raster_.lowest_at(i, j) >= h; };
    bool any = false;
    for (int v = 0; v < mask_.rows(); ++v)
      for (int u = 0; u < mask_.columns(); ++u) {
        const int i = i0_ + u / 3, j = j0_ + v / 3;
        const int dx = u % 3 == 0 ? -1 : (u % 3 == 2 ? 1 : 0);
        const int dy = v % 3 == 0 ? -1 : (v % 3 == 2 ? 1 : 0);
        const bool set = square(i, j) && (dx == 0 || square(i + dx, j)) &&
                         (dy == 0 || square(i, j + dy)) &&
                         (dx == 0 || dy == 0 || square(i + dx, j + dy));
        mask_.set(u, v, set);
        any = any || set;
      }
    return any;
  }

  LatticeMask& mask() { return mask_; }

 private:
  static std::vector<double> lines(double origin, int k0, int k1, double side, double epsilon) {
    std::vector<double> out;
    for (int k = k0; k < k1; ++k) {
      const double lo = origin + k * side, hi = origin + (k + 1) * side;
      out.insert(out.end(), {lo, lo + epsilon, hi - epsilon});
    }
    out.push_back(origin + k1 * side);
    return out;
  }

  const TerrainRaster& raster_;
  int i0_, j0_;
  LatticeMask mask_;
};

/// The squares of side `square` (grown to stay within kMaxSquares) covering `area`, from its
/// lower corner; no heights yet.
TerrainRaster square_grid(const Box2& area, double square) {
  TerrainRaster r;
  if (area.empty() || !(square > 0)) return r;
  const double w = area.max.x - area.min.x, h = area.max.y - area.min.y;
  double side = square;
  while ((std::ceil(w / side) + 1) * (std::ceil(h / side) + 1) > kMaxSquares) side *= 1.25;
  r.square = side;
  r.columns = std::max(1, static_cast<int>(std::ceil(w / side)));
  r.rows = std::max(1, static_cast<int>(std::ceil(h / side)));
  r.area = {area.min, {area.min.x + r.columns * side, area.min.y + r.rows * side}};
  return r;
}

/// Square (i, j) of `r`, grown by `grow` on every side.
Box2 square_box(const TerrainRaster& r, int i, int j, double grow) {
  return {{r.area.min.x + i * r.square - grow, r.area.min.y + j * r.square - grow},
          {r.area.min.x + (i + 1) * r.square + grow, r.area.min.y + (j + 1) * r.square + grow}};
}

/// Calls f(k, piece) for every triangle of the TIN and every square k (row-major) of `r`,
/// grown by `grow`, that it meets: `piece` is the triangle clipped to that grown square, its
/// corners on the triangle. A triangle touching a square's side only still gives that side its
/// heights (an empty piece is not passed on).
template <class F>
void for_each_piece(const Terrain& terrain, const TerrainRaster& r, double grow, F&& f) {
  const double side = r.square;
  auto column = [&](double x) { return static_cast<int>(std::floor((x - r.area.min.x) / side)); };
  auto row = [&](double y) { return static_cast<int>(std::floor((y - r.area.min.y) / side)); };
  const Box2 reach = r.area.grown(grow);
  for (const Triangle3& t : terrain.triangles) {
    Box2 b;
    for (const Vec3& v : t.v) b.extend(Vec2{v.x, v.y});
    if (!b.overlaps(reach)) continue;
    const int i0 = std::max(0, column(b.min.x - grow) - 1);
    const int i1 = std::min(r.columns - 1, column(b.max.x + grow));
    const int j0 = std::max(0, row(b.min.y - grow) - 1);
    const int j1 = std::min(r.rows - 1, row(b.max.y + grow));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const ClipPolygon piece = clip_to_box(t, square_box(r, i, j, grow));
        if (piece.n == 0) continue;
        f(static_cast<std::size_t>(j) * static_cast<std::size_t>(r.columns) +
              static_cast<std::size_t>(i),
          piece);
      }
  }
}

}  // namespace

TerrainRaster terrain_raster(const Terrain& terrain, const Box2& area, double square) {
  TerrainRaster r = square_grid(area, square);
  if (r.columns == 0) return r;
  const std::size_t count = static_cast<std::size_t>(r.columns) * static_cast<std::size_t>(r.rows);
  r.lowest.assign(count, std::numeric_limits<double>::infinity());
  std::vector<double> covered(count, 0.0);
  for_each_piece(terrain, r, 0, [&](std::size_t k, const ClipPolygon& piece) {
    for (int c = 0; c < piece.n; ++c)
      r.lowest[k] = std::min(r.lowest[k], piece.p[static_cast<std::size_t>(c)].z);
    covered[k] += area_of(piece);
  });
  // A square the TIN leaves partly open has no known ground there: it holds nothing up.
  for (std::size_t k = 0; k < count; ++k)
    if (covered[k] < kCovered * r.square * r.square)
      r.lowest[k] = -std::numeric_limits<double>::infinity();
  return r;
}

std::vector<Occluder> terrain_occluders(const Terrain& terrain, const Box2& area, double step,
                                        double epsilon) {
  std::vector<Occluder> out;
  if (terrain.empty() || area.empty() || !(step > 0) || !(epsilon > 0)) return out;
  // Squares of 4ε: wider than 2ε, so the three columns of a square never overlap, and fine
  // enough that the ε lost along a level's outline is a quarter of a square.
  const TerrainRaster r = terrain_raster(terrain, area, 4 * epsilon);
  if (r.columns == 0) return out;
  const int tile = std::max(1, static_cast<int>(std::lround(kTileSide / r.square)));
  for (int j0 = 0; j0 < r.rows; j0 += tile)
    for (int i0 = 0; i0 < r.columns; i0 += tile) {
      const int i1 = std::min(r.columns, i0 + tile), j1 = std::min(r.rows, j0 + tile);
      // The levels that can differ in this tile: up to its highest square; below the lowest
      // known square of the tile and its neighbours every level is the same set.
      double high = -std::numeric_limits<double>::infinity();
      double low = std::numeric_limits<double>::infinity();
      for (int j = std::max(0, j0 - 1); j < std::min(r.rows, j1 + 1); ++j)
        for (int i = std::max(0, i0 - 1); i < std::min(r.columns, i1 + 1); ++i) {
          const double z = r.lowest_at(i, j);
          if (z == -std::numeric_limits<double>::infinity()) continue;
          if (i >= i0 && i < i1 && j >= j0 && j < j1) high = std::max(high, z);
          low = std::min(low, z);
        }
      if (!(high > -std::numeric_limits<double>::infinity())) continue;
      const auto k_high = static_cast<long long>(std::floor(high / step));
      const auto k_low = static_cast<long long>(std::ceil(low / step));
      TileMask levels(r, i0, i1, j0, j1, epsilon);
      std::vector<unsigned char> above;  // the level above's cells: equal ones hide no more
      for (long long k = k_high; k >= k_low; --k) {
        const double h = static_cast<double>(k) * step;
        if (!levels.erode(h) || levels.mask().cells() == above) continue;
        above = levels.mask().cells();
        const bool full = levels.mask().full();
        levels.mask().separate_diagonals();
        std::vector<Polygon> shapes;
        // Rings that do not assemble are left out: an occluder may always be smaller.
        if (levels.mask().polygons(shapes))
          for (Polygon& p : shapes) {
            const Box2 box = bounds(p);
            out.push_back({kTerrainBlock, h, std::move(p), box});
          }
        if (full) break;  // every lower level is this whole tile again
      }
    }
  return out;
}

std::vector<Occluder> terrain_plane_occluders(const Terrain& terrain, const Box2& area,
                                              double square, double epsilon) {
  std::vector<Occluder> out;
  if (terrain.empty() || !(epsilon > 0)) return out;
  const TerrainRaster r = square_grid(area, square);
  if (r.columns == 0) return out;
  const std::size_t count = static_cast<std::size_t>(r.columns) * static_cast<std::size_t>(r.rows);
  // Pass 1: each square's mean gradient, the gradients of the TIN's pieces in it weighted by
  // their areas (the plane the terrain leans along there; any gradient stays conservative,
  // pass 2 lowers the plane under the terrain whatever it is).
  std::vector<Vec2> gradient(count, Vec2{0, 0});
  std::vector<double> covered(count, 0.0);
  for_each_piece(terrain, r, 0, [&](std::size_t k, const ClipPolygon& piece) {
    const double a = area_of(piece);
    // The piece's plane (its corners lie on one triangle), by Newell's normal. Cliffs (no
    // area in plan) carry no slope.
    double nx = 0, ny = 0, nz = 0;
    for (int c = 0; c < piece.n; ++c) {
      const Point3& u = piece.p[static_cast<std::size_t>(c)];
      const Point3& v = piece.p[static_cast<std::size_t>((c + 1) % piece.n)];
      nx += (u.y - v.y) * (u.z + v.z);
      ny += (u.z - v.z) * (u.x + v.x);
      nz += (u.x - v.x) * (u.y + v.y);
    }
    if (std::abs(nz) > 1e-9 * (std::abs(nx) + std::abs(ny)))  // so nz != 0 too
      gradient[k] += a * Vec2{-nx / nz, -ny / nz};
    covered[k] += a;
  });
  // Pass 2: over the square grown by ε (a box holding the disk of radius ε around each of its
  // points), the least of terrain - plane. terrain - plane is linear on each piece, so its least
  // value is at a piece's corner.
  std::vector<double> least(count, std::numeric_limits<double>::infinity());
  std::vector<double> covered_grown(count, 0.0);
  for (std::size_t k = 0; k < count; ++k)
    if (covered[k] > 0) gradient[k] /= covered[k];
  auto square_at = [&](std::size_t k) {
    return square_box(r, static_cast<int>(k % static_cast<std::size_t>(r.columns)),
                      static_cast<int>(k / static_cast<std::size_t>(r.columns)), 0);
  };
  auto origin = [&](std::size_t k) {
    const Box2 b = square_at(k);
    return 0.5 * (b.min + b.max);
  };
  for_each_piece(terrain, r, epsilon, [&](std::size_t k, const ClipPolygon& piece) {
    const Vec2 o = origin(k), g = gradient[k];
    for (int c = 0; c < piece.n; ++c) {
      const Point3& v = piece.p[static_cast<std::size_t>(c)];
      least[k] = std::min(least[k], v.z - (g.x * (v.x - o.x) + g.y * (v.y - o.y)));
    }
    covered_grown[k] += area_of(piece);
  });
  const double grown_side = r.square + 2 * epsilon;
  for (std::size_t k = 0; k < count; ++k) {
    // The terrain must be known within ε of every point of the square (so in it too).
    if (covered_grown[k] < kCovered * grown_side * grown_side) continue;
    const Vec2 g = gradient[k];
    const Box2 box = square_at(k);
    Occluder o;
    o.block = kTerrainBlock;
    // For p in the square and q within ε: plane(p) <= plane(q) + ε·|g| <= terrain(q) once the
    // plane is lowered by ε·|g| below its least value over the grown square (thesis 7.4). The
    // rounding of the clipped corners is a few ulps of a height: 0.1 µm more covers it.
    o.top_z = least[k] - epsilon * std::hypot(g.x, g.y) - 1e-7;
    o.slope = g;
    o.origin = origin(k);
    o.shape.outer = box.corners();
    o.bounds = box;
    out.push_back(std::move(o));
  }
  return out;
}

}  // namespace urbanpvs::geometry
