// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/ViewCellSamples.hpp"

#include <cmath>

namespace urbanpvs::geometry {

std::size_t top_edge_sample_count(const Vec3& a, const Vec3& b, double epsilon) {
  const double length =
      std::sqrt((b.x - a.x) * (b.x - a.x) + (b.y - a.y) * (b.y - a.y) + (b.z - a.z) * (b.z - a.z));
  // Spacing length / n <= 2ε puts every point of the edge within ε of a sample.
  const double steps = std::ceil(length / (2 * epsilon));
  return static_cast<std::size_t>(std::max(1.0, steps)) + 1;
}

void sample_top_edge(const Vec3& a, const Vec3& b, double epsilon, std::vector<Vec3>& out) {
  const std::size_t n = top_edge_sample_count(a, b, epsilon) - 1;
  out.push_back(a);
  for (std::size_t i = 1; i < n; ++i) {
    const double t = double(i) / double(n);
    out.push_back({std::lerp(a.x, b.x, t), std::lerp(a.y, b.y, t), std::lerp(a.z, b.z, t)});
  }
  out.push_back(b);
}

}  // namespace urbanpvs::geometry
