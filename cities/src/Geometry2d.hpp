// Small 2D helpers for convex polygons, the only shapes the layout cuts.
//
// Only +, -, *, / and sqrt are used (all correctly rounded by IEEE 754), never trigonometry or
// pow, whose results differ between C libraries: this keeps generated coordinates bit-identical
// across platforms. The library is compiled with -ffp-contract=off for the same reason.
#pragma once

#include <cmath>
#include <optional>
#include <vector>

#include "urbanpvs/cities/Model.hpp"

namespace urbanpvs::cities::detail {

inline Vec2 operator+(Vec2 a, Vec2 b) {
  return {a.x + b.x, a.y + b.y};
}
inline Vec2 operator-(Vec2 a, Vec2 b) {
  return {a.x - b.x, a.y - b.y};
}
inline Vec2 operator*(Vec2 a, double s) {
  return {a.x * s, a.y * s};
}
inline double dot(Vec2 a, Vec2 b) {
  return a.x * b.x + a.y * b.y;
}
inline double cross(Vec2 a, Vec2 b) {
  return a.x * b.y - a.y * b.x;
}
inline double length(Vec2 a) {
  return std::sqrt(dot(a, a));
}
inline Vec2 normalized(Vec2 a) {
  const double l = length(a);
  return {a.x / l, a.y / l};
}
/// The direction rotated by +90°: for an edge of a counter-clockwise ring it points inside.
inline Vec2 leftNormal(Vec2 d) {
  return {-d.y, d.x};
}
inline Vec2 midpoint(Vec2 a, Vec2 b) {
  return {(a.x + b.x) * 0.5, (a.y + b.y) * 0.5};
}

/// Rounds to whole millimetres. Every stored coordinate passes through here exactly once, so
/// points shared by neighbours are computed once and then copied, never recomputed.
inline double snapMm(double v) {
  return std::round(v * 1000.0) / 1000.0;
}
inline Vec2 snapMm(Vec2 p) {
  return {snapMm(p.x), snapMm(p.y)};
}
Ring snapMm(const Ring& ring);

/// The signed area (positive for counter-clockwise rings), m².
double signedArea(const Ring& ring);

/// Area centroid of a simple ring.
Vec2 centroid(const Ring& ring);

/// The part of a convex ring where dot(n, p) >= c (Sutherland-Hodgman against one plane).
Ring clipHalfPlane(const Ring& ring, Vec2 n, double c);

/// Splits a convex ring by the line dot(n, p) == c into the part below (dot < c) and above. The
/// two crossing points are computed once, snapped, and inserted into both halves, so the halves
/// share their cut edge exactly. Returns nothing when the line misses the interior.
struct ConvexSplit {
  Ring below;
  Ring above;
};
std::optional<ConvexSplit> splitConvex(const Ring& ring, Vec2 n, double c);

/// Insets a convex counter-clockwise ring, edge i moving inwards by depth[i]. Fails (nullopt)
/// when an edge would shrink below min_edge or flip, i.e. when the inset is no longer the same
/// polygon shape. The result is not snapped.
std::optional<Ring> insetConvex(const Ring& ring, const std::vector<double>& depth,
                                double min_edge);

/// Removes vertices of a convex ring that make edges shorter than min_edge or turn by less than
/// asin(min_sin_turn): both make later insets ill-conditioned. Removing a vertex of a convex
/// polygon only cuts off a triangle, so the result stays inside the input.
Ring simplifyConvex(Ring ring, double min_edge, double min_sin_turn);

/// Smallest signed distance from p to the lines of a convex counter-clockwise ring's edges
/// (positive inside): how far p is from the boundary.
double insideDistance(const Ring& convex, Vec2 p);

/// Extent of a ring along a unit direction: [min, max] of dot(dir, p).
struct Extent {
  double lo;
  double hi;
};
Extent extentAlong(const Ring& ring, Vec2 dir);

/// Unit direction of the longest edge.
Vec2 longestEdgeDirection(const Ring& ring);

/// Whether a counter-clockwise ring is strictly convex (all turns left).
bool isStrictlyConvex(const Ring& ring);

}  // namespace urbanpvs::cities::detail
