// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/validate/RayScene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace urbanpvs::validate {
namespace {

using Vertex = Vec3;
using Rings = std::vector<std::vector<Vertex>>;

// A wall whose foot is at most this far (m) above the ground near it stands on the ground:
// below it lies earth. Higher feet are those of raised parts (passages, pilotis, skyways), with
// open space below them. Matches what a person can walk under.
constexpr double kOnGround = 1.0;
// Faces with |n_z| over |n| below this are walls (tilted by up to 11.5°).
constexpr double kWallTilt = 0.2;
// Skirts reach this far (m) below the lowest point of the city: below every viewpoint.
constexpr double kSkirtDepth = 100;
// The ground near an object is judged from the bases of the objects within this distance (m).
constexpr double kGroundReach = 50;
// Box filters and grid cells grow by this (m), against rounding at their edges.
constexpr double kBoxSlack = 0.01;

Vertex newell_normal(const std::vector<Vertex>& ring) {
  Vertex n{0, 0, 0};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Vertex& a = ring[i];
    const Vertex& b = ring[(i + 1) % ring.size()];
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

double length(const Vertex& v) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}
double dot(const Vertex& a, const Vertex& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vertex cross(const Vertex& a, const Vertex& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// The unit normal of a ring, or {0, 0, 0} when the ring has no area: the Newell
// normal is the ring's vector area, so its length compared with the ring's size says whether
// the polygon is a sliver.
Vertex unit_normal(const std::vector<Vertex>& ring) {
  if (ring.size() < 3) return {0, 0, 0};
  const Vertex n = newell_normal(ring);
  const double len = length(n);
  double extent = 0;
  for (int k = 0; k < 3; ++k) {
    double lo = ring[0][k], hi = ring[0][k];
    for (const Vertex& v : ring) lo = std::min(lo, v[k]), hi = std::max(hi, v[k]);
    extent = std::max(extent, hi - lo);
  }
  // Twice the area below 1e-9 of the squared extent: a line, not a surface.
  if (!(len > 1e-9 * extent * extent)) return {0, 0, 0};
  return {n[0] / len, n[1] / len, n[2] / len};
}

int dominant_axis(const Vertex& n) {
  const double ax = std::abs(n[0]), ay = std::abs(n[1]), az = std::abs(n[2]);
  return az >= ax && az >= ay ? 2 : (ay >= ax ? 1 : 0);
}

// The two coordinates kept when dropping axis `drop`.
Vec2 project(double x, double y, double z, int drop) {
  if (drop == 0) return {y, z};
  if (drop == 1) return {z, x};
  return {x, y};
}

// Even-odd inside test of a point against rings (outer and holes alike: a point in a hole is
// inside two rings, so outside).
template <class RingAt>
bool inside_even_odd(std::size_t ring_count, RingAt&& ring_at, Vec2 p) {
  bool in = false;
  for (std::size_t r = 0; r < ring_count; ++r) {
    const auto [begin, end] = ring_at(r);
    if (end - begin < 3) continue;
    for (const Vec2 *a = begin, *b = end - 1; a != end; b = a++)
      if ((a->y > p.y) != (b->y > p.y) && p.x < (b->x - a->x) * (p.y - a->y) / (b->y - a->y) + a->x)
        in = !in;
  }
  return in;
}

void add_box_faces(const Box3& box, double spacing, std::vector<Vec3>& out) {
  const double x0 = box.xy.min.x, x1 = box.xy.max.x, y0 = box.xy.min.y, y1 = box.xy.max.y;
  const double z0 = box.zmin, z1 = box.zmax;
  const Rings faces[] = {
      {{{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}}},
      {{{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}},
      {{{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}}},
      {{{x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}}},
      {{{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}}},
      {{{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}}},
  };
  for (const Rings& f : faces)
    for (const Vec3& p : surface_points(geometry::Surface3{f}, spacing)) out.push_back(p);
}

}  // namespace

std::vector<Vec3> surface_points(const geometry::Surface3& surface, double spacing) {
  std::vector<Vec3> out;
  if (surface.rings.empty() || surface.rings.front().empty()) return out;
  // The boundary, vertices included: thin surfaces (a wall strip under a roof step, narrower
  // than the lattice) are still sampled.
  for (const std::vector<Vertex>& ring : surface.rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vertex& a = ring[i];
      const Vertex& b = ring[(i + 1) % ring.size()];
      const Vertex e{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      const int n = std::max(1, static_cast<int>(std::ceil(length(e) / spacing)));
      for (int k = 0; k < n; ++k) {
        const double s = double(k) / n;
        out.push_back({a[0] + s * e[0], a[1] + s * e[1], a[2] + s * e[2]});
      }
    }
  const std::vector<Vertex>& outer = surface.rings.front();
  const Vertex n = unit_normal(outer);
  if (dot(n, n) == 0) return out;
  // An orthonormal frame (u, w) in the plane through the outer ring's centroid.
  Vertex c{0, 0, 0};
  for (const Vertex& v : outer)
    for (int k = 0; k < 3; ++k) c[k] += v[k] / double(outer.size());
  Vertex helper{0, 0, 0};
  const double an[] = {std::abs(n[0]), std::abs(n[1]), std::abs(n[2])};
  helper[an[0] <= an[1] && an[0] <= an[2] ? 0 : (an[1] <= an[2] ? 1 : 2)] = 1;
  Vertex u = cross(n, helper);
  const double ulen = length(u);
  u = {u[0] / ulen, u[1] / ulen, u[2] / ulen};
  const Vertex w = cross(n, u);
  std::vector<std::vector<Vec2>> flat;
  Box2 box;
  for (const std::vector<Vertex>& ring : surface.rings) {
    flat.emplace_back();
    for (const Vertex& v : ring) {
      const Vertex r{v[0] - c[0], v[1] - c[1], v[2] - c[2]};
      flat.back().push_back({dot(r, u), dot(r, w)});
      box.extend(flat.back().back());
    }
  }
  auto ring_at = [&](std::size_t r) {
    return std::pair<const Vec2*, const Vec2*>{flat[r].data(), flat[r].data() + flat[r].size()};
  };
  const double du = box.max.x - box.min.x, dw = box.max.y - box.min.y;
  const int nu = std::max(1, static_cast<int>(std::ceil(du / spacing)));
  const int nw = std::max(1, static_cast<int>(std::ceil(dw / spacing)));
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nw; ++j) {
      const Vec2 q{box.min.x + (i + 0.5) * du / nu, box.min.y + (j + 0.5) * dw / nw};
      if (!inside_even_odd(flat.size(), ring_at, q)) continue;
      out.push_back({c[0] + q.x * u[0] + q.y * w[0], c[1] + q.x * u[1] + q.y * w[1],
                     c[2] + q.x * u[2] + q.y * w[2]});
    }
  return out;
}

std::vector<Vec3> box_points(const Box3& box, double spacing) {
  std::vector<Vec3> out;
  if (!box.xy.empty() && box.zmin <= box.zmax) add_box_faces(box, spacing, out);
  return out;
}

RayScene::Segment::Segment(const Vec3& from, const Vec3& to, double t_max)
    : p(from), d{to.x - from.x, to.y - from.y, to.z - from.z} {
  const double a[] = {p.x, p.y, p.z},
               e[] = {p.x + t_max * d.x, p.y + t_max * d.y, p.z + t_max * d.z};
  for (int k = 0; k < 3; ++k) lo[k] = std::min(a[k], e[k]), hi[k] = std::max(a[k], e[k]);
}

RayScene::RayScene(const geometry::City& city) {
  // The ground level each object's wall feet are compared with: its own lowest point, unless
  // that lies more than kOnGround above the median base of the objects around it (within
  // kGroundReach): then the object is raised as a whole (a skyway of its own) and the median is
  // the ground. The median, not the lowest base, so that one sunken building (a basement
  // entrance, 2 m down in the 3D BAG) does not take the ground away from its neighbours; and
  // never below the median, so that an object reaching into a basement still has ground under
  // its walls at street level.
  std::vector<Box3> extent(city.objects.size());  // of each blocking object's surfaces
  Box2 all;
  for (const geometry::CityObject& o : city.objects) {
    if (!blocks(o)) continue;
    for (const geometry::Surface3& s : o.surfaces)
      for (const auto& ring : s.rings)
        for (const Vertex& v : ring) extent[o.index].extend(Vec2{v[0], v[1]}, v[2]);
    all.extend(extent[o.index].xy);
  }
  int gx = 1, gy = 1;
  if (!all.empty()) {
    gx = std::max(1, static_cast<int>(std::ceil((all.max.x - all.min.x) / kGroundReach)));
    gy = std::max(1, static_cast<int>(std::ceil((all.max.y - all.min.y) / kGroundReach)));
  }
  auto ground_cell = [&](double v, double origin, int n) {
    return std::clamp(static_cast<int>(std::floor((v - origin) / kGroundReach)), 0, n - 1);
  };
  std::vector<std::vector<double>> bases(static_cast<std::size_t>(gx) *
                                         static_cast<std::size_t>(gy));
  for (const geometry::CityObject& o : city.objects) {
    const Box3& e = extent[o.index];
    if (e.xy.empty()) continue;
    const int x = ground_cell(0.5 * (e.xy.min.x + e.xy.max.x), all.min.x, gx);
    const int y = ground_cell(0.5 * (e.xy.min.y + e.xy.max.y), all.min.y, gy);
    bases[static_cast<std::size_t>(y * gx + x)].push_back(e.zmin);
  }
  std::vector<double> around;
  auto ground_level = [&](const Box3& e) {
    around.clear();
    const int x0 = ground_cell(e.xy.min.x - kGroundReach, all.min.x, gx);
    const int x1 = ground_cell(e.xy.max.x + kGroundReach, all.min.x, gx);
    const int y0 = ground_cell(e.xy.min.y - kGroundReach, all.min.y, gy);
    const int y1 = ground_cell(e.xy.max.y + kGroundReach, all.min.y, gy);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const std::vector<double>& b = bases[static_cast<std::size_t>(y * gx + x)];
        around.insert(around.end(), b.begin(), b.end());
      }
    if (around.empty()) return e.zmin;
    auto mid = around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2);
    std::nth_element(around.begin(), mid, around.end());
    const double median = *mid;
    return e.zmin > median + kOnGround ? median : std::max(e.zmin, median);
  };

  // The terrain (a CityJSON TINRelief or a DEM), when the city has one, is the earth itself: each
  // triangle stops every segment, as a skirt does. On a slope the median of the neighbours'
  // bases says nothing about a building's ground (Monaco: bases 50 m apart within 50 m), so
  // there an object stands on the ground when its lowest point is within kOnGround of the
  // highest terrain under it, and is raised above that terrain otherwise.
  const std::vector<double> terrain_top = add_terrain(city, extent);
  auto ground_of = [&](const geometry::CityObject& o) {
    const Box3& e = extent[o.index];
    const double top = terrain_top[o.index];
    if (top == -std::numeric_limits<double>::infinity()) return ground_level(e);
    return e.zmin <= top + kOnGround ? e.zmin : top;
  };

  double lowest = std::numeric_limits<double>::infinity();
  for (const Box3& e : extent) lowest = std::min(lowest, e.zmin);
  for (const Face& f : skirts_) lowest = std::min(lowest, f.lo[2]);
  const double deep = lowest - kSkirtDepth;
  object_faces_.reserve(city.objects.size() + 1);
  for (const geometry::CityObject& o : city.objects) {
    object_faces_.push_back(static_cast<std::uint32_t>(faces_.size()));
    if (!blocks(o)) {
      if (!o.bbox.xy.empty() && o.bbox.zmin <= o.bbox.zmax) boxes_.push_back({o.bbox, o.index});
      continue;
    }
    if (extent[o.index].xy.empty()) continue;
    for (const geometry::Surface3& s : o.surfaces) add_face(s.rings, o.index, s.blocks);
    const double ground = ground_of(o);
    for (const geometry::Surface3& s : o.surfaces) {
      if (s.rings.empty() || !s.blocks) continue;
      const Vertex n = unit_normal(s.rings.front());
      if (dot(n, n) > 0 && std::abs(n[2]) < kWallTilt)
        add_skirts(s.rings.front(), n, ground + kOnGround, deep, o.index);
    }
  }
  object_faces_.push_back(static_cast<std::uint32_t>(faces_.size()));
  box_of_.assign(city.objects.size(), -1);
  for (std::size_t i = 0; i < boxes_.size(); ++i)
    box_of_[boxes_[i].object] = static_cast<std::int32_t>(i);

  for (const Face& f : faces_) bounds_.extend(Box2{{f.lo[0], f.lo[1]}, {f.hi[0], f.hi[1]}});
  for (const Face& f : skirts_) bounds_.extend(Box2{{f.lo[0], f.lo[1]}, {f.hi[0], f.hi[1]}});
  for (const TargetBox& b : boxes_) bounds_.extend(b.box.xy);
  if (bounds_.empty()) bounds_ = {{0, 0}, {1, 1}};
  nx_ = std::max(1, static_cast<int>(std::ceil((bounds_.max.x - bounds_.min.x) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((bounds_.max.y - bounds_.min.y) / cell_)));
  grid_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  auto insert = [&](const Box2& raw, std::uint32_t entry) {
    const Box2 b = raw.grown(kBoxSlack);
    const int x0 = std::clamp(static_cast<int>((b.min.x - bounds_.min.x) / cell_), 0, nx_ - 1);
    const int x1 = std::clamp(static_cast<int>((b.max.x - bounds_.min.x) / cell_), 0, nx_ - 1);
    const int y0 = std::clamp(static_cast<int>((b.min.y - bounds_.min.y) / cell_), 0, ny_ - 1);
    const int y1 = std::clamp(static_cast<int>((b.max.y - bounds_.min.y) / cell_), 0, ny_ - 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) grid_[static_cast<std::size_t>(y * nx_ + x)].push_back(entry);
  };
  for (std::uint32_t i = 0; i < faces_.size(); ++i)
    insert(Box2{{faces_[i].lo[0], faces_[i].lo[1]}, {faces_[i].hi[0], faces_[i].hi[1]}}, kFace | i);
  for (std::uint32_t i = 0; i < skirts_.size(); ++i)
    insert(Box2{{skirts_[i].lo[0], skirts_[i].lo[1]}, {skirts_[i].hi[0], skirts_[i].hi[1]}},
           kSkirt | i);
  for (std::uint32_t i = 0; i < boxes_.size(); ++i) insert(boxes_[i].box.xy, kBox | i);
  face_stamp_.assign(faces_.size(), 0);
  skirt_stamp_.assign(skirts_.size(), 0);
  box_stamp_.assign(boxes_.size(), 0);
}

std::vector<double> RayScene::add_terrain(const geometry::City& city,
                                          const std::vector<Box3>& extent) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> top(city.objects.size(), -kInf);
  const std::vector<geometry::Triangle3>& tin = city.terrain.triangles;
  if (tin.empty()) return top;
  Box2 all;
  std::vector<Box3> boxes(tin.size());
  for (std::size_t i = 0; i < tin.size(); ++i) {
    for (const Vertex& v : tin[i].v) boxes[i].extend(Vec2{v[0], v[1]}, v[2]);
    all.extend(boxes[i].xy);
    Face f;
    if (make_face({{tin[i].v[0], tin[i].v[1], tin[i].v[2]}}, 0, f)) skirts_.push_back(f);
  }
  // Buckets of kGroundReach over the TIN, for the highest terrain under each object.
  const int nx = std::max(1, int(std::ceil((all.max.x - all.min.x) / kGroundReach)));
  const int ny = std::max(1, int(std::ceil((all.max.y - all.min.y) / kGroundReach)));
  auto column = [&](double x) {
    return std::clamp(int(std::floor((x - all.min.x) / kGroundReach)), 0, nx - 1);
  };
  auto row = [&](double y) {
    return std::clamp(int(std::floor((y - all.min.y) / kGroundReach)), 0, ny - 1);
  };
  std::vector<std::vector<std::uint32_t>> buckets(std::size_t(nx) * std::size_t(ny));
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    for (int y = row(boxes[i].xy.min.y); y <= row(boxes[i].xy.max.y); ++y)
      for (int x = column(boxes[i].xy.min.x); x <= column(boxes[i].xy.max.x); ++x)
        buckets[std::size_t(y) * std::size_t(nx) + std::size_t(x)].push_back(i);
  for (const geometry::CityObject& o : city.objects) {
    const Box2& e = extent[o.index].xy;
    if (e.empty() || !e.overlaps(all)) continue;
    for (int y = row(e.min.y); y <= row(e.max.y); ++y)
      for (int x = column(e.min.x); x <= column(e.max.x); ++x)
        for (std::uint32_t i : buckets[std::size_t(y) * std::size_t(nx) + std::size_t(x)])
          if (boxes[i].xy.overlaps(e)) top[o.index] = std::max(top[o.index], boxes[i].zmax);
  }
  terrain_ = tin;  // for ground_at
  terrain_bounds_ = all;
  terrain_nx_ = nx, terrain_ny_ = ny;
  terrain_grid_ = std::move(buckets);
  return top;
}

double RayScene::ground_at(Vec2 p) const {
  double ground = -std::numeric_limits<double>::infinity();
  if (terrain_.empty() || p.x < terrain_bounds_.min.x || p.x > terrain_bounds_.max.x ||
      p.y < terrain_bounds_.min.y || p.y > terrain_bounds_.max.y)
    return ground;
  const int x =
      std::clamp(int(std::floor((p.x - terrain_bounds_.min.x) / kGroundReach)), 0, terrain_nx_ - 1);
  const int y =
      std::clamp(int(std::floor((p.y - terrain_bounds_.min.y) / kGroundReach)), 0, terrain_ny_ - 1);
  for (std::uint32_t i :
       terrain_grid_[std::size_t(y) * std::size_t(terrain_nx_) + std::size_t(x)]) {
    const auto& v = terrain_[i].v;
    const Vec2 a{v[0].x, v[0].y}, b{v[1].x, v[1].y}, c{v[2].x, v[2].y};
    const double d = geometry::cross(b - a, c - a);
    if (d == 0) continue;  // upright: its edges are those of the triangles beside it
    const double l1 = geometry::cross(p - a, c - a) / d, l2 = geometry::cross(b - a, p - a) / d;
    const double l0 = 1 - l1 - l2;
    constexpr double kOnEdge = 1e-9;  // a point on a shared edge belongs to both triangles
    if (l0 < -kOnEdge || l1 < -kOnEdge || l2 < -kOnEdge) continue;
    ground = std::max(ground, l0 * v[0].z + l1 * v[1].z + l2 * v[2].z);
  }
  return ground;
}

bool RayScene::make_face(const Rings& rings, std::uint32_t object, Face& f) {
  if (rings.empty()) return false;
  const Vertex n = unit_normal(rings.front());
  if (dot(n, n) == 0) return false;  // no area: blocks nothing
  f.normal = n;
  Vertex c{0, 0, 0};
  for (const Vertex& v : rings.front())
    for (int k = 0; k < 3; ++k) c[k] += v[k] / double(rings.front().size());
  f.offset = dot(n, c);
  f.drop = dominant_axis(n);
  f.first_ring = static_cast<std::uint32_t>(ring_start_.empty() ? 0 : ring_start_.size() - 1);
  if (ring_start_.empty()) ring_start_.push_back(0);
  f.lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  f.hi = {-f.lo[0], -f.lo[1], -f.lo[2]};
  for (const std::vector<Vertex>& ring : rings) {
    if (ring.size() < 3) continue;
    for (const Vertex& v : ring) {
      ring_vertex_.push_back(project(v[0], v[1], v[2], f.drop));
      for (int k = 0; k < 3; ++k)
        f.lo[k] = std::min(f.lo[k], v[k]), f.hi[k] = std::max(f.hi[k], v[k]);
    }
    ring_start_.push_back(static_cast<std::uint32_t>(ring_vertex_.size()));
  }
  f.end_ring = static_cast<std::uint32_t>(ring_start_.size() - 1);
  // Hits lie on the plane, which a non-planar input polygon leaves by up to `warp`.
  double warp = 0;
  for (const std::vector<Vertex>& ring : rings)
    for (const Vertex& v : ring) warp = std::max(warp, std::abs(dot(n, v) - f.offset));
  for (int k = 0; k < 3; ++k) f.lo[k] -= kBoxSlack + warp, f.hi[k] += kBoxSlack + warp;
  f.object = object;
  return true;
}

void RayScene::add_face(const Rings& rings, std::uint32_t object, bool blocks) {
  Face f;
  f.blocks = blocks;
  if (make_face(rings, object, f)) faces_.push_back(f);
}

void RayScene::add_skirts(const std::vector<Vertex>& wall, const Vertex& normal,
                          double highest_foot, double deep, std::uint32_t object) {
  // The wall in its own frame: along it (horizontal) and up. A bottom edge has the wall above
  // it and nothing below it; orientation-free, as files get ring orientation wrong.
  Vertex along{-normal[1], normal[0], 0};
  const double len = std::hypot(along[0], along[1]);
  along = {along[0] / len, along[1] / len, 0};
  std::vector<Vec2> flat;
  double extent = 0;
  for (const Vertex& v : wall) {
    flat.push_back({along[0] * v[0] + along[1] * v[1], v[2]});
    extent = std::max({extent, std::abs(flat.back().x - flat.front().x),
                       std::abs(flat.back().y - flat.front().y)});
  }
  auto ring_at = [&](std::size_t) {
    return std::pair<const Vec2*, const Vec2*>{flat.data(), flat.data() + flat.size()};
  };
  const double probe = 1e-4 * extent;
  for (std::size_t i = 0; i < wall.size(); ++i) {
    const std::size_t j = (i + 1) % wall.size();
    const Vec2 a = flat[i], b = flat[j];
    if (std::abs(b.x - a.x) <= probe) continue;  // a vertical edge: a side, not a foot
    if (std::min(wall[i][2], wall[j][2]) > highest_foot) continue;
    const Vec2 mid{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
    if (!inside_even_odd(1, ring_at, {mid.x, mid.y + probe}) ||
        inside_even_odd(1, ring_at, {mid.x, mid.y - probe}))
      continue;
    Face f;
    const Rings skirt{
        {wall[i], wall[j], {wall[j][0], wall[j][1], deep}, {wall[i][0], wall[i][1], deep}}};
    if (make_face(skirt, object, f)) skirts_.push_back(f);
  }
}

bool RayScene::inside_rings(std::uint32_t first_ring, std::uint32_t end_ring, Vec2 p) const {
  return inside_even_odd(
      end_ring - first_ring,
      [&](std::size_t r) {
        const Vec2* base = ring_vertex_.data();
        return std::pair<const Vec2*, const Vec2*>{base + ring_start_[first_ring + r],
                                                   base + ring_start_[first_ring + r + 1]};
      },
      p);
}

double RayScene::face_hit(const Face& f, const Segment& s, double t_max) const {
  for (int k = 0; k < 3; ++k)
    if (s.hi[k] < f.lo[k] || s.lo[k] > f.hi[k]) return kNone;
  const double along = f.normal[0] * s.d.x + f.normal[1] * s.d.y + f.normal[2] * s.d.z;
  if (along == 0) return kNone;  // parallel to the plane: it grazes, nothing is stopped
  const double from = f.normal[0] * s.p.x + f.normal[1] * s.p.y + f.normal[2] * s.p.z - f.offset;
  const double t = -from / along;
  if (!(t > 0 && t < t_max)) return kNone;
  const double x = s.p.x + t * s.d.x, y = s.p.y + t * s.d.y, z = s.p.z + t * s.d.z;
  // The point on the plane must lie in the face's box before its rings are worth a look.
  if (x < f.lo[0] || x > f.hi[0] || y < f.lo[1] || y > f.hi[1] || z < f.lo[2] || z > f.hi[2])
    return kNone;
  return inside_rings(f.first_ring, f.end_ring, project(x, y, z, f.drop)) ? t : kNone;
}

double RayScene::box_entry(const Box3& box, const Segment& s, double t_max) {
  double t0 = 0, t1 = t_max;
  const double p[] = {s.p.x, s.p.y, s.p.z}, d[] = {s.d.x, s.d.y, s.d.z};
  const double lo[] = {box.xy.min.x, box.xy.min.y, box.zmin};
  const double hi[] = {box.xy.max.x, box.xy.max.y, box.zmax};
  for (int k = 0; k < 3; ++k) {
    if (d[k] == 0) {
      if (p[k] < lo[k] || p[k] > hi[k]) return kNone;
      continue;
    }
    double a = (lo[k] - p[k]) / d[k], b = (hi[k] - p[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return kNone;
  }
  return t0 < t_max ? t0 : kNone;
}

double RayScene::own_hit(std::uint32_t object, const Segment& s, double t_max) const {
  if (box_of_[object] >= 0)
    return box_entry(boxes_[static_cast<std::size_t>(box_of_[object])].box, s, t_max);
  double best = kNone;
  for (std::uint32_t i = object_faces_[object]; i < object_faces_[object + 1]; ++i)
    best = std::min(best, face_hit(faces_[i], s, std::min(t_max, best)));
  return best;
}

template <class F>
void RayScene::walk(const Segment& s, const double* horizon, F&& visit) const {
  if (++query_ == 0) {  // the stamps wrapped around: forget them
    std::fill(face_stamp_.begin(), face_stamp_.end(), 0);
    std::fill(skirt_stamp_.begin(), skirt_stamp_.end(), 0);
    std::fill(box_stamp_.begin(), box_stamp_.end(), 0);
    query_ = 1;
  }
  // Only the part of the segment over the grid.
  double t0 = 0, t1 = 1;
  if (!geometry::clip_line_to_box({s.p.x, s.p.y}, {s.d.x, s.d.y}, bounds_, 1.0, &t0, &t1)) return;
  const double x = (s.p.x - bounds_.min.x) / cell_, y = (s.p.y - bounds_.min.y) / cell_;
  const double dx = s.d.x / cell_, dy = s.d.y / cell_;
  int ix = std::clamp(static_cast<int>(std::floor(x + t0 * dx)), 0, nx_ - 1);
  int iy = std::clamp(static_cast<int>(std::floor(y + t0 * dy)), 0, ny_ - 1);
  const int stepx = dx > 0 ? 1 : -1, stepy = dy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  // Parameters where the segment crosses the next vertical and horizontal cell lines.
  double tmx = dx != 0 ? (ix + (dx > 0 ? 1 : 0) - x) / dx : inf;
  double tmy = dy != 0 ? (iy + (dy > 0 ? 1 : 0) - y) / dy : inf;
  const double tdx = dx != 0 ? 1 / std::abs(dx) : inf, tdy = dy != 0 ? 1 / std::abs(dy) : inf;
  for (;;) {
    for (std::uint32_t entry : grid_[static_cast<std::size_t>(iy * nx_ + ix)]) {
      const std::uint32_t i = entry & ~kKindMask;
      std::vector<std::uint32_t>& stamp = (entry & kKindMask) == kFace    ? face_stamp_
                                          : (entry & kKindMask) == kSkirt ? skirt_stamp_
                                                                          : box_stamp_;
      if (stamp[i] == query_) continue;
      stamp[i] = query_;
      if (visit(entry)) return;
    }
    const double next = std::min(tmx, tmy);
    if (next > t1 || next > *horizon) return;
    if (tmx < tmy)
      tmx += tdx, ix += stepx;
    else
      tmy += tdy, iy += stepy;
    if (ix < 0 || iy < 0 || ix >= nx_ || iy >= ny_) return;
  }
}

double RayScene::blocker_hit(std::uint32_t entry, const Segment& s, std::uint32_t object,
                             double t_max) const {
  const std::uint32_t i = entry & ~kKindMask;
  switch (entry & kKindMask) {
    case kFace:
      return faces_[i].object != object && faces_[i].blocks ? face_hit(faces_[i], s, t_max) : kNone;
    case kSkirt:  // the earth stops every segment, its own building's too
      return face_hit(skirts_[i], s, t_max);
    default:
      return kNone;  // boxes block nothing
  }
}

double RayScene::some_blocker_before(const Segment& s, std::uint32_t object, double t_max) const {
  if (!(t_max > 0)) return kNone;
  // Neighbouring targets of a hidden object are mostly hidden by the same blocker: trying it
  // first spares most walks through the grid.
  if (last_blocker_ != kNoBlocker)
    if (const double t = blocker_hit(last_blocker_, s, object, t_max); t < t_max) return t;
  double hit = kNone;
  walk(s, &t_max, [&](std::uint32_t entry) {
    hit = blocker_hit(entry, s, object, t_max);
    if (hit < t_max) last_blocker_ = entry;
    return hit < t_max;
  });
  return hit < t_max ? hit : kNone;
}

bool RayScene::reaches(const Vec3& p, const Vec3& q, std::uint32_t object) const {
  const double len =
      std::sqrt((q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y) + (q.z - p.z) * (q.z - p.z));
  if (len <= kCoincident) return true;
  const double slack = kCoincident / len;
  const double end = 1 - slack;
  const Segment s(p, q, 1.0);
  const double blocker = some_blocker_before(s, object, end);
  if (blocker >= end) return true;
  // Something of another object lies on the way: still seen when the segment meets the object
  // itself before that (a target on its far side, reached through its own near side), and
  // nothing else lies before that. Only the part up to the blocker found can hold such a hit,
  // which keeps the object's faces out of reach of most of its own targets' segments.
  const double own = own_hit(object, Segment(p, q, blocker), blocker);
  if (own >= blocker) return false;
  return some_blocker_before(s, object, own - slack) >= kNone;
}

void RayScene::first_met(const Vec3& p, const Vec3& q,
                         std::vector<std::pair<std::uint32_t, double>>& met) const {
  const Segment s(p, q, 1.0);
  double nearest = kNone;
  std::uint32_t nearest_object = 0;
  bool nearest_is_face = false;
  std::vector<std::pair<std::uint32_t, double>> boxes;
  walk(s, &nearest, [&](std::uint32_t entry) {
    const std::uint32_t i = entry & ~kKindMask;
    const double limit = std::min(nearest, 1.0);
    switch (entry & kKindMask) {
      case kFace:
        if (!faces_[i].blocks) {  // met, but the segment goes on, as through a box
          if (const double t = face_hit(faces_[i], s, limit); t < kNone)
            boxes.emplace_back(faces_[i].object, t);
        } else if (const double t = face_hit(faces_[i], s, limit); t < nearest) {
          nearest = t, nearest_object = faces_[i].object, nearest_is_face = true;
        }
        break;
      case kSkirt:
        // The earth stops the segment; nothing of the building is seen there.
        if (const double t = face_hit(skirts_[i], s, limit); t < nearest)
          nearest = t, nearest_is_face = false;
        break;
      default:
        if (const double t = box_entry(boxes_[i].box, s, limit); t < kNone)
          boxes.emplace_back(boxes_[i].object, t);
        break;
    }
    return false;
  });
  for (const auto& [object, t] : boxes)
    if (t <= nearest) met.emplace_back(object, t);
  if (nearest_is_face) met.emplace_back(nearest_object, nearest);
}

}  // namespace urbanpvs::validate
