// SPDX-License-Identifier: GPL-3.0-or-later
// The cull map of a view cell (thesis 5.5): z = min over samples P of max over occluders O of
// the shadow height f(O, P). Max: for one sample, a point is hidden if any occluder hides it.
// Min: for the cell, a point is hidden only if it is hidden from every sample; with occluders
// shrunk by ε and samples at most 2ε apart on the cell's top edges this covers every viewpoint
// in the cell (thesis 5.2.1, 5.3, 7.2). This is the CPU form of the thesis's two-pass stencil
// merge; other backends must produce the same map.
#pragma once

#include <span>
#include <vector>

#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"
#include "urbanpvs/preprocess/visibility/OccluderShadow.hpp"
#include "urbanpvs/preprocess/visibility/SampleHorizon.hpp"

namespace urbanpvs::preprocess {

struct CullMapStats {
  std::size_t shadows = 0;            ///< shadow polygons rasterized
  std::size_t pixels_written = 0;     ///< pixel centres covered, summed over shadows
  std::size_t occluders_skipped = 0;  ///< hidden from a sample (front to back only)
};

/// Which occluders a sample's pass may leave out, drawing front to back (thesis 5.6.1: occluded
/// occluders add nothing). Every choice stays conservative.
enum class OccluderSkipping {
  None,           ///< draw every occluder: the brute-force map by definition
  HiddenInMap,    ///< skip those hidden in the sample's map so far (render_sample_front_to_back)
  BehindHorizon,  ///< skip those the sample's horizon hides (render_sample_unhidden): same map
};

/// Writes the max over all occluder shadows seen from `sample` into `map` (which the caller
/// fills with CullMap::kNothingHidden first). Shadows are clipped one pixel beyond the map.
void render_sample(const Vec3& sample, std::span<const geometry::Occluder* const> occluders,
                   CullMap& map, CullMapStats* stats = nullptr);

/// The same, nearest occluders first, skipping every occluder already hidden in the map built so
/// far (its box, one pixel larger, under the map everywhere). Skipping an occluder can only
/// lower the map, so this stays conservative; it renders far fewer shadows in a city, where
/// the first row of buildings hides most of the rest (thesis 5.6.1, per sample).
void render_sample_front_to_back(const Vec3& sample,
                                 std::span<const geometry::Occluder* const> occluders, CullMap& map,
                                 CullMapStats* stats = nullptr);

/// The same map as render_sample, nearest occluders first, leaving out every occluder that the
/// sample's horizon (SampleHorizon, over the occluders drawn so far) proves hidden at its top:
/// along every sight line through its walls a drawn wall is crossed first and rises faster, so
/// its shadow lies under theirs at every point, pixel centres included. Exact where
/// render_sample_front_to_back, which judges by pixel centres, can lose a shadow.
void render_sample_unhidden(const Vec3& sample,
                            std::span<const geometry::Occluder* const> occluders, CullMap& map,
                            SampleHorizon& horizon, CullMapStats* stats = nullptr);

/// The merged cull map of a cell from its samples (min over samples of the per-sample max).
/// No samples: nothing is hidden.
CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                      std::span<const geometry::Occluder* const> occluders,
                      CullMapStats* stats = nullptr,
                      OccluderSkipping skipping = OccluderSkipping::None);
/// The same over every occluder of a list.
CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                      std::span<const geometry::Occluder> occluders, CullMapStats* stats = nullptr);

/// Pointers to every element of `occluders` (the form the functions above take).
std::vector<const geometry::Occluder*> pointers_to(std::span<const geometry::Occluder> occluders);

}  // namespace urbanpvs::preprocess
