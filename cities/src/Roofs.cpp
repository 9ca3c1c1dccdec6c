#include "Roofs.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "Geometry2d.hpp"
#include "SolidBuilder.hpp"

namespace urbanpvs::cities::detail {
namespace {

Vec3 at(Vec2 p, double z) {
  return {p.x, p.y, z};
}

std::vector<Vec3> lifted(const Ring& ring, double z) {
  std::vector<Vec3> out;
  out.reserve(ring.size());
  for (const Vec2& p : ring) out.push_back(at(p, z));
  return out;
}

// Walls with a horizontal top at z0 + height under every edge of every ring.
void addFlatWalls(SolidBuilder& builder, const Polygon& footprint, double z0, double height) {
  auto ring_walls = [&](const Ring& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vec2 a = ring[i];
      const Vec2 b = ring[(i + 1) % ring.size()];
      builder.addWall(a, b, z0, {at(a, z0 + height), at(b, z0 + height)});
    }
  };
  ring_walls(footprint.outer);
  for (const Ring& hole : footprint.holes) ring_walls(hole);
}

}  // namespace

Polygon stripFootprint(const Strip& strip) {
  Polygon fp;
  fp.outer = strip.outer;
  Ring inner_reversed(strip.inner.rbegin(), strip.inner.rend());
  if (strip.closed) {
    fp.holes.push_back(std::move(inner_reversed));
  } else {
    fp.outer.insert(fp.outer.end(), inner_reversed.begin(), inner_reversed.end());
  }
  return fp;
}

Solid flatSolid(const Polygon& footprint, double z0, double height) {
  SolidBuilder builder;
  addGround(builder, footprint, z0);
  addFlatWalls(builder, footprint, z0, height);
  std::vector<std::vector<Vec3>> roof{lifted(footprint.outer, z0 + height)};
  for (const Ring& hole : footprint.holes) roof.push_back(lifted(hole, z0 + height));
  builder.addFace(SurfaceType::Roof, roof);
  return builder.release();
}

// ---------------------------------------------------------------------------------------------
// Strip roofs (perimeter blocks).
//
// The ridge runs at half depth. Because the street line, the ridge line and the courtyard line
// of one block side are parallel, each roof face between two stations is planar, and at a corner
// the ridge point is the midpoint of the corner diagonal, which lies on both sides' ridge lines:
// the diagonal becomes a hip on the street side and a valley on the courtyard side.

namespace {

// Distance between the street line and the courtyard line of segment k.
double segmentDepth(const Strip& strip, std::size_t k) {
  const std::size_t next = (k + 1) % strip.outer.size();
  const Vec2 dir = normalized(strip.outer[next] - strip.outer[k]);
  return std::fabs(cross(dir, strip.inner[k] - strip.outer[k]));
}

}  // namespace

std::optional<RoofedSolid> stripSolid(const Strip& strip, double z0, double eaves, double ridge,
                                      RoofKind kind) {
  const std::size_t m = strip.outer.size();
  if (m < 2 || strip.inner.size() != m || (strip.closed && m < 3)) return std::nullopt;
  std::vector<Vec2> mid(m);
  for (std::size_t k = 0; k < m; ++k) mid[k] = snapMm(midpoint(strip.outer[k], strip.inner[k]));

  const double ze = z0 + eaves;
  const double zr = z0 + ridge;
  // Hip ends: the ridge stops half a depth short of the end wall, which then stays low.
  bool hips = !strip.closed && kind == RoofKind::Hipped;
  Vec2 ridge_start = mid[0];
  Vec2 ridge_end = mid[m - 1];
  if (hips) {
    const double d_start = segmentDepth(strip, 0);
    const double d_end = segmentDepth(strip, m - 2);
    const double first_len = length(mid[1] - mid[0]);
    const double last_len = length(mid[m - 1] - mid[m - 2]);
    const bool fits = m == 2 ? first_len >= 0.5 * (d_start + d_end) + 1.0
                             : first_len >= 0.5 * d_start + 1.0 && last_len >= 0.5 * d_end + 1.0;
    if (fits) {
      ridge_start = snapMm(mid[0] + normalized(mid[1] - mid[0]) * (0.5 * d_start));
      ridge_end = snapMm(mid[m - 1] + normalized(mid[m - 2] - mid[m - 1]) * (0.5 * d_end));
    } else {
      hips = false;
    }
  }

  const Polygon fp = stripFootprint(strip);
  SolidBuilder builder;
  addGround(builder, fp, z0);
  const std::size_t segments = strip.closed ? m : m - 1;
  for (std::size_t k = 0; k < segments; ++k) {
    const std::size_t next = (k + 1) % m;
    builder.addWall(strip.outer[k], strip.outer[next], z0,
                    {at(strip.outer[k], ze), at(strip.outer[next], ze)});
    builder.addWall(strip.inner[next], strip.inner[k], z0,
                    {at(strip.inner[next], ze), at(strip.inner[k], ze)});
    const Vec2 a = (k == 0 && !strip.closed) ? ridge_start : mid[k];
    const Vec2 b = (next == m - 1 && !strip.closed) ? ridge_end : mid[next];
    builder.addFace(SurfaceType::Roof,
                    {{at(strip.outer[k], ze), at(strip.outer[next], ze), at(b, zr), at(a, zr)}});
    builder.addFace(SurfaceType::Roof,
                    {{at(strip.inner[next], ze), at(strip.inner[k], ze), at(a, zr), at(b, zr)}});
  }
  if (!strip.closed) {
    const Vec2 o0 = strip.outer[0];
    const Vec2 i0 = strip.inner[0];
    const Vec2 on = strip.outer[m - 1];
    const Vec2 in = strip.inner[m - 1];
    if (hips) {
      builder.addWall(i0, o0, z0, {at(i0, ze), at(o0, ze)});
      builder.addWall(on, in, z0, {at(on, ze), at(in, ze)});
      builder.addFace(SurfaceType::Roof, {{at(i0, ze), at(o0, ze), at(ridge_start, zr)}});
      builder.addFace(SurfaceType::Roof, {{at(on, ze), at(in, ze), at(ridge_end, zr)}});
    } else {  // pentagonal gable walls
      builder.addWall(i0, o0, z0, {at(i0, ze), at(mid[0], zr), at(o0, ze)});
      builder.addWall(on, in, z0, {at(on, ze), at(mid[m - 1], zr), at(in, ze)});
    }
  }
  if (!builder.isClosed()) return std::nullopt;
  const RoofKind used = strip.closed || hips ? RoofKind::Hipped : RoofKind::Gabled;
  return RoofedSolid{builder.release(), used, ridge};
}

// ---------------------------------------------------------------------------------------------
// Gabled roofs over convex slices. The roof is z = ridge - k * |s(p)|, s the signed distance to
// the ridge line: two planes. Every ring is augmented with the points where it crosses the ridge
// line; those become the apexes of gable walls and the corners of both roof halves.

namespace {

struct RidgeVertex {
  Vec2 p;
  int side;  // +1 / -1: which roof half; 0: on the ridge line
};

struct RidgeRing {
  std::vector<RidgeVertex> vertices;
  int crossings = 0;
};

// The chain of a ridge-augmented convex ring on one side, from the crossing where the ring enters
// that side to the one where it leaves, both inclusive.
std::vector<RidgeVertex> sideChain(const RidgeRing& ring, int side) {
  const std::vector<RidgeVertex>& v = ring.vertices;
  const std::size_t n = v.size();
  std::size_t start = n;
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i].side == 0 && v[(i + 1) % n].side == side) start = i;
  }
  std::vector<RidgeVertex> chain;
  if (start == n) return chain;
  chain.push_back(v[start]);
  for (std::size_t k = 1; k < n; ++k) {
    const RidgeVertex& x = v[(start + k) % n];
    chain.push_back(x);
    if (x.side == 0) break;
  }
  return chain;
}

}  // namespace

std::optional<RoofedSolid> gabledSolid(const Polygon& footprint, Vec2 ridge_point, Vec2 ridge_dir,
                                       double z0, double eaves, double ridge) {
  if (footprint.holes.size() > 1) return std::nullopt;
  const Vec2 n = leftNormal(ridge_dir);
  auto offset = [&](Vec2 p) { return dot(n, p - ridge_point); };
  double reach = 0.0;
  for (const Vec2& p : footprint.outer) reach = std::max(reach, std::fabs(offset(p)));
  if (reach <= 0.0) return std::nullopt;
  const double k = (ridge - eaves) / reach;
  auto roof_z = [&](const RidgeVertex& v) {
    return v.side == 0 ? z0 + ridge : z0 + ridge - k * std::fabs(offset(v.p));
  };

  SolidBuilder builder;
  addGround(builder, footprint, z0);
  // Augments a ring with its ridge crossings and builds the walls under it.
  auto augment = [&](const Ring& ring, RidgeRing& out) {
    const std::size_t count = ring.size();
    for (std::size_t i = 0; i < count; ++i) {
      const Vec2 a = ring[i];
      const Vec2 b = ring[(i + 1) % count];
      const double sa = offset(a);
      const double sb = offset(b);
      // A vertex (almost) on the ridge line would give a sliver face: let the caller move it.
      if (std::fabs(sa) < 0.05) return false;
      const RidgeVertex va{a, sa > 0.0 ? 1 : -1};
      out.vertices.push_back(va);
      std::vector<Vec3> top{at(a, roof_z(va))};
      if ((sa > 0.0) != (sb > 0.0)) {
        const RidgeVertex x{snapMm(a + (b - a) * (sa / (sa - sb))), 0};
        out.vertices.push_back(x);
        ++out.crossings;
        top.push_back(at(x.p, roof_z(x)));
      }
      const RidgeVertex vb{b, sb > 0.0 ? 1 : -1};
      top.push_back(at(b, roof_z(vb)));
      builder.addWall(a, b, z0, top);
    }
    return out.crossings == 2;
  };
  RidgeRing outer;
  if (!augment(footprint.outer, outer)) return std::nullopt;
  RidgeRing hole;
  if (!footprint.holes.empty() && !augment(footprint.holes.front(), hole)) return std::nullopt;

  for (const int side : {1, -1}) {
    std::vector<RidgeVertex> half = sideChain(outer, side);
    if (!footprint.holes.empty()) {
      const std::vector<RidgeVertex> hole_chain = sideChain(hole, side);
      half.insert(half.end(), hole_chain.begin(), hole_chain.end());
    }
    std::vector<Vec3> ring;
    for (const RidgeVertex& v : half) ring.push_back(at(v.p, roof_z(v)));
    builder.addFace(SurfaceType::Roof, {ring});
  }
  if (!builder.isClosed()) return std::nullopt;
  return RoofedSolid{builder.release(), RoofKind::Gabled, ridge};
}

// ---------------------------------------------------------------------------------------------
// Hipped roofs over convex slices: the roof is the lower envelope of planes rising at equal
// slope from every edge. For a convex polygon the face of edge i is the polygon clipped by the
// half-planes where edge i's distance is the smallest, so each face is a few convex clips.

std::optional<RoofedSolid> hippedSolid(const Ring& convex, double z0, double eaves, double slope,
                                       double max_rise) {
  const std::size_t n = convex.size();
  std::vector<Vec2> normal(n);  // inward unit normals
  for (std::size_t i = 0; i < n; ++i) {
    normal[i] = leftNormal(normalized(convex[(i + 1) % n] - convex[i]));
  }
  std::vector<Ring> faces(n);
  double reach = 0.0;  // largest distance from the boundary: where the ridge is
  for (std::size_t i = 0; i < n; ++i) {
    Ring face = convex;
    for (std::size_t j = 0; j < n && face.size() >= 3; ++j) {
      if (j == i) continue;
      // Keep dist_i(p) <= dist_j(p).
      face = clipHalfPlane(face, normal[j] - normal[i],
                           dot(normal[j], convex[j]) - dot(normal[i], convex[i]));
    }
    for (const Vec2& p : face) reach = std::max(reach, dot(normal[i], p - convex[i]));
    faces[i] = std::move(face);
  }
  if (reach <= 0.5) return std::nullopt;
  const double k = std::min(slope, max_rise / reach);
  const double ridge = snapMm(k * reach);
  const double ze = z0 + eaves;

  SolidBuilder builder;
  const Polygon fp{convex, {}};
  addGround(builder, fp, z0);
  addFlatWalls(builder, fp, z0, eaves);
  for (std::size_t i = 0; i < n; ++i) {
    if (faces[i].size() < 3) continue;
    std::vector<Vec3> ring;
    for (const Vec2& p : faces[i]) {
      // Clipped points are snapped here, once per face; the faces agree on shared skeleton
      // nodes to far below a millimetre, and isClosed() rejects the rare case they do not.
      const Vec2 q = snapMm(p);
      const double rise = std::max(0.0, k * dot(normal[i], p - convex[i]));
      ring.push_back(at(q, ze + rise));
    }
    builder.addFace(SurfaceType::Roof, {ring});
  }
  if (!builder.isClosed()) return std::nullopt;
  return RoofedSolid{builder.release(), RoofKind::Hipped, eaves + ridge};
}

}  // namespace urbanpvs::cities::detail
