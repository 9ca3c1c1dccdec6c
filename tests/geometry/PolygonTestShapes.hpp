// SPDX-License-Identifier: GPL-3.0-or-later
// Random polygons for property tests: star-shaped rings (always simple), convex rings and
// integer rectangles, all from a seeded generator so failures reproduce.
#pragma once

#include <cmath>
#include <numbers>
#include <random>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry::test {

/// A star-shaped ring around `c`: angles strictly increasing, radii in [rmin, rmax]. Simple by
/// construction (every ray from c meets it once), counter-clockwise.
inline Ring star_ring(std::mt19937_64& rng, Vec2 c, double rmin, double rmax, int n) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> angles;
  // Sorted angles make a simple ring around c only if no angular gap reaches pi; else c lies
  // outside and the ring may turn clockwise. Draw again until the gaps are small enough.
  for (bool ok = false; !ok;) {
    angles.assign(static_cast<std::size_t>(std::max(n, 3)), 0.0);
    for (double& a : angles) a = u(rng) * 2 * std::numbers::pi;
    std::sort(angles.begin(), angles.end());
    angles.erase(
        std::unique(angles.begin(), angles.end(), [](double a, double b) { return b - a < 1e-3; }),
        angles.end());
    ok = angles.size() >= 3 &&
         angles.front() + 2 * std::numbers::pi - angles.back() < 0.9 * std::numbers::pi;
    for (std::size_t i = 1; ok && i < angles.size(); ++i)
      ok = angles[i] - angles[i - 1] < 0.9 * std::numbers::pi;
  }
  Ring r;
  for (double a : angles) {
    const double rad = rmin + (rmax - rmin) * u(rng);
    r.push_back({c.x + rad * std::cos(a), c.y + rad * std::sin(a)});
  }
  return r;
}

/// A random convex ring (points on a circle at sorted random angles), counter-clockwise.
inline Ring convex_ring(std::mt19937_64& rng, Vec2 c, double radius, int n) {
  return star_ring(rng, c, radius, radius, n);
}

/// A star polygon, with probability 1/2 carrying a star hole well inside its kernel.
inline Polygon random_star_polygon(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double rmax = 5 + 60 * u(rng);
  const double rmin = rmax * (0.3 + 0.6 * u(rng));
  Polygon p{star_ring(rng, {1000 * u(rng), 1000 * u(rng)}, rmin, rmax, 3 + int(20 * u(rng))), {}};
  if (u(rng) < 0.5) {
    // Centroid of a star ring is not necessarily in its kernel; the circle of radius
    // rmin * cos(pi / n) around the centre generating it is. Use the ring's own average.
    Vec2 c{0, 0};
    for (Vec2 v : p.outer) c = c + (1.0 / double(p.outer.size())) * v;
    double inner = 1e300;
    for (std::size_t i = 0; i < p.outer.size(); ++i)
      inner =
          std::min(inner, distance_to_segment(c, p.outer[i], p.outer[(i + 1) % p.outer.size()]));
    if (inside_ring(p.outer, c) && inner > 2) {
      Ring hole = star_ring(rng, c, 0.2 * inner, 0.6 * inner, 3 + int(8 * u(rng)));
      if (hole.size() >= 3) {
        std::reverse(hole.begin(), hole.end());
        p.holes.push_back(std::move(hole));
      }
    }
  }
  return p;
}

}  // namespace urbanpvs::geometry::test
