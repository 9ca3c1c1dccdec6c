// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/RoofShapes.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>

namespace urbanpvs::geometry {
namespace {

// A vertex this close outside the chord of its neighbours is dropped from a quadrilateral (m):
// mapped rectangles carry such points where a neighbour's wall meets them.
constexpr double kOnSide = 0.1;
// A vertex this close inside the chord of its neighbours is dropped too (m): OSM stores
// coordinates to 1e-7 degrees, about 1 cm, so a straight wall's points wander by as much.
constexpr double kOnChord = 0.02;
// A quadrilateral's corners must be right angles within this (cosine of 80°).
constexpr double kRightAngle = 0.1737;
// Heights within this (m) of the eaves count as the eaves: no wall above them.
constexpr double kAtEaves = 0.001;

// How far p lies left of the line from a to b (m): inside a counter-clockwise ring's side,
// negative outside it.
double left_of(Vec2 p, Vec2 a, Vec2 b) {
  return cross(b - a, p - a) / glm::length(b - a);
}

// The ring (counter-clockwise) without the vertices that lie within kOnSide outside the chord
// of their neighbours, or within kOnChord inside it: the ring left lies within the footprint up
// to the rounding of its coordinates, so a roof over it overhangs no wall.
Ring corners_of(Ring r) {
  for (bool dropped = true; dropped && r.size() > 3;) {
    dropped = false;
    for (std::size_t i = 0; i < r.size() && r.size() > 3; ++i) {
      const Vec2 prev = r[(i + r.size() - 1) % r.size()], next = r[(i + 1) % r.size()];
      const double inside = left_of(r[i], prev, next);
      if (inside < kOnChord && -inside < kOnSide &&
          dot(r[i] - prev, next - r[i]) > 0) {  // between them, not a spike
        r.erase(r.begin() + static_cast<std::ptrdiff_t>(i));
        dropped = true;
      }
    }
  }
  return r;
}

bool convex(const Ring& r) {
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()], c = r[(i + 2) % r.size()];
    if (cross(b - a, c - b) <= 0) return false;
  }
  return true;
}

// Whether every vertex of `r` lies outside the convex quadrilateral `q` or within kOnChord of
// its boundary: a roof over `q` then overhangs no wall beyond the coordinates' rounding, however
// the dropped vertices' small offsets added up.
bool within_footprint(const std::array<Vec2, 4>& q, const Ring& r) {
  for (Vec2 v : r) {
    double inside = INFINITY;  // distance to the nearest side, when inside every side
    for (std::size_t i = 0; i < 4; ++i) inside = std::min(inside, left_of(v, q[i], q[(i + 1) % 4]));
    if (inside > kOnChord) return false;
  }
  return true;
}

// The corners of a footprint that is a rectangle up to kOnSide and kRightAngle, counter-
// clockwise, the first edge one of the two longer sides (of the shorter ones: `across`).
std::optional<std::array<Vec2, 4>> rectangle(const Polygon& p, bool across) {
  if (!p.holes.empty()) return std::nullopt;
  const Ring r = corners_of(p.outer);
  if (r.size() != 4 || !convex(r)) return std::nullopt;
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec2 e = r[(i + 1) % 4] - r[i], f = r[(i + 2) % 4] - r[(i + 1) % 4];
    if (std::abs(dot(e, f)) > kRightAngle * glm::length(e) * glm::length(f)) return std::nullopt;
  }
  const double first = glm::length(r[1] - r[0]) + glm::length(r[3] - r[2]);
  const double second = glm::length(r[2] - r[1]) + glm::length(r[0] - r[3]);
  const std::size_t s = (first >= second) != across ? 0 : 1;
  const std::array<Vec2, 4> q{r[s], r[s + 1], r[(s + 2) % 4], r[(s + 3) % 4]};
  if (!within_footprint(q, p.outer)) return std::nullopt;
  return q;
}

Vec3 at(Vec2 p, double z) {
  return {p.x, p.y, z};
}

// Gabled: the ridge joins the middles of the sides bc and da at the top; the sides ab and cd
// are the eaves, bc and da the gable walls.
ShapedRoof gabled(const std::array<Vec2, 4>& q, double eaves, double top) {
  const auto [a, b, c, d] = q;
  const Vec2 m1 = 0.5 * (d + a), m2 = 0.5 * (b + c);
  ShapedRoof roof;
  roof.faces = {{at(a, eaves), at(b, eaves), at(m2, top), at(m1, top)},
                {at(c, eaves), at(d, eaves), at(m1, top), at(m2, top)}};
  roof.walls = {{at(b, eaves), at(c, eaves), at(m2, top)},
                {at(d, eaves), at(a, eaves), at(m1, top)}};
  return roof;
}

// A pyramid: a triangle from each side of the convex ring up to the apex over its centroid, at
// the top. Each side must face the apex, so the triangles tile the ring.
std::optional<ShapedRoof> pyramid(const Ring& r, double eaves, double top) {
  const double area2 = signed_area2(r);
  if (!(area2 > 0)) return std::nullopt;
  Vec2 centroid{0, 0};
  for (std::size_t i = 0; i < r.size(); ++i)
    centroid += cross(r[i], r[(i + 1) % r.size()]) * (r[i] + r[(i + 1) % r.size()]);
  centroid /= 3 * area2;
  ShapedRoof roof;
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 a = r[i], b = r[(i + 1) % r.size()];
    if (!(cross(b - a, centroid - a) > 0)) return std::nullopt;
    roof.faces.push_back({at(a, eaves), at(b, eaves), at(centroid, top)});
  }
  return roof;
}

// Skillion: one plane, highest on the side the roof turns its back on, at the eaves on the side
// it faces; walls above the eaves along every edge up to it.
ShapedRoof skillion(const Ring& r, double direction_deg, double eaves, double top) {
  const double t = direction_deg * (M_PI / 180);
  const Vec2 downhill{std::sin(t), std::cos(t)};  // x east, y north
  double lo = INFINITY, hi = -INFINITY;
  for (Vec2 v : r) lo = std::min(lo, dot(v, downhill)), hi = std::max(hi, dot(v, downhill));
  auto z = [&](Vec2 v) {
    return hi > lo ? top - (top - eaves) * (dot(v, downhill) - lo) / (hi - lo) : eaves;
  };
  ShapedRoof roof;
  roof.faces.emplace_back();
  for (Vec2 v : r) roof.faces.back().push_back(at(v, z(v)));
  for (std::size_t i = 0; i < r.size(); ++i) {
    const Vec2 u = r[i], v = r[(i + 1) % r.size()];
    std::vector<Vec3> wall{at(u, eaves), at(v, eaves)};
    if (z(v) > eaves + kAtEaves) wall.push_back(at(v, z(v)));
    if (z(u) > eaves + kAtEaves) wall.push_back(at(u, z(u)));
    if (wall.size() >= 3) roof.walls.push_back(std::move(wall));
  }
  return roof;
}

}  // namespace

std::optional<ShapedRoof> shaped_roof(const Polygon& footprint, const RoofShapeTags& tags,
                                      double eaves, double top) {
  if (!(top > eaves) || footprint.outer.size() < 3) return std::nullopt;
  const std::string& s = tags.shape;
  const bool gabled_family = s == "gabled" || s == "round" || s == "gambrel";
  const bool hipped_family = s == "hipped" || s == "half-hipped" || s == "mansard";
  if (gabled_family && tags.ridge != RidgeOrientation::Unknown) {
    if (auto q = rectangle(footprint, tags.ridge == RidgeOrientation::Across))
      return gabled(*q, eaves, top);
  } else if (gabled_family || hipped_family) {
    // The ridge's direction (untagged) or length (a hip's slope is not tagged): the pyramid over
    // the rectangle is the lower envelope of every such roof.
    if (auto q = rectangle(footprint, false))
      return pyramid(Ring(q->begin(), q->end()), eaves, top);
  } else if (s == "pyramidal") {
    if (footprint.holes.empty() && convex(corners_of(footprint.outer)))
      return pyramid(footprint.outer, eaves, top);
  } else if (s == "skillion" && tags.direction && footprint.holes.empty()) {
    return skillion(footprint.outer, *tags.direction, eaves, top);
  }
  return std::nullopt;
}

std::optional<double> roof_direction(std::string_view text) {
  double degrees = 0;
  const char* end = text.data() + text.size();
  if (auto [p, ec] = std::from_chars(text.data(), end, degrees); ec == std::errc{} && p == end) {
    if (!std::isfinite(degrees)) return std::nullopt;
    return std::fmod(std::fmod(degrees, 360.0) + 360.0, 360.0);
  }
  static constexpr std::array<const char*, 16> kPoints = {"n",  "nne", "ne", "ene", "e",  "ese",
                                                          "se", "sse", "s",  "ssw", "sw", "wsw",
                                                          "w",  "wnw", "nw", "nnw"};
  auto same = [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == static_cast<unsigned char>(b);
  };
  for (std::size_t i = 0; i < kPoints.size(); ++i)
    if (std::equal(text.begin(), text.end(), kPoints[i], kPoints[i] + std::strlen(kPoints[i]),
                   same))
      return 22.5 * static_cast<double>(i);
  return std::nullopt;
}

}  // namespace urbanpvs::geometry
