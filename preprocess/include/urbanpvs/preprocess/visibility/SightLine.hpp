// SPDX-License-Identifier: GPL-3.0-or-later
// One sight line against the occluders, exactly: the test a cull map makes at one pixel centre
// for one sample (thesis 4.2.1: a point lies in an edge's shadow when the line from the sample
// to it passes the edge below the wall's top). The sample horizons use it where their sectors
// cannot decide a pixel centre, so that far from the cell they judge exactly as the brute-force
// map does.
#pragma once

#include <cstdint>
#include <span>

#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/preprocess/visibility/OccluderShadow.hpp"
#include "urbanpvs/preprocess/visibility/SpatialIndex.hpp"

namespace urbanpvs::preprocess {

/// True when the segment from `from` to `to` crosses an occluder wall that casts a shadow from
/// `from` (casts_shadow: it faces `from`, or `from` is above the occluder's top) more than
/// `margin` below the wall's top: the walls a cull map draws, so that the hierarchical test
/// never hides more than the brute-force map. `tree` indexes `occluders`
/// (BakeScene::occluder_index()). With `blocker`, the occluder it names (an index; any other
/// value: none) is tried first, and when the line is blocked it names one that blocks it; the
/// answer is the same either way.
bool sight_line_blocked(const Vec3& from, const Vec3& to, const BoxQuadtree& tree,
                        std::span<const geometry::Occluder> occluders, double margin,
                        std::uint32_t* blocker = nullptr);

}  // namespace urbanpvs::preprocess
