// SPDX-License-Identifier: GPL-3.0-or-later
// Sample points on a view cell's top edges (thesis 5.3): with 2.5D occluders, what is hidden from
// every point of the top face's boundary is hidden from the whole prism, and what is hidden from
// every sample is hidden from every point within ε of one once the occluders are shrunk by ε
// (thesis 7.2). So each top edge gets samples at most 2ε apart, both endpoints included.
#pragma once

#include <cstddef>
#include <vector>

#include "urbanpvs/geometry/cells/ViewCells.hpp"

namespace urbanpvs::geometry {

/// Number of samples on the segment a→b (3D): n + 1 for n = max(1, ceil(|ab| / 2ε)) equal steps.
/// `epsilon` > 0.
std::size_t top_edge_sample_count(const Vec3& a, const Vec3& b, double epsilon);

/// Appends the samples of a→b to `out`: a, evenly spaced interior points, b (the endpoints
/// bit-identical to a and b). Deterministic: the same a, b, epsilon give the same bits.
void sample_top_edge(const Vec3& a, const Vec3& b, double epsilon, std::vector<Vec3>& out);

}  // namespace urbanpvs::geometry
