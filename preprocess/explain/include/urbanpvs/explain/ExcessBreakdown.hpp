// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-explain's core: where a PVS's excess comes from (issue 18). The excess of a viewpoint
// is what its cell's PVS holds and the validator did not see from it. Each such object is put
// down to the first of these mechanisms that accounts for it, in this order:
//  1. seen-finer: a sliver the viewpoint's targets fell between. Targets at a finer spacing
//     (ExplainOptions::finer_spacing), from the same viewpoint, see it. Not excess at all.
//  2. elsewhere-in-cell: the cell is large. It is seen from another point of the cell: the top
//     corners, the middles of the top edges and random points of the prism. The PVS must hold
//     it; only a smaller cell leaves it out (thesis 5.9).
//  3. epsilon: occluders shrunk by ε (thesis 7.3). The cell, baked again with unshrunk
//     occluders (same samples, same pixel), leaves it out.
//  4. far-field: the horizons beyond the largest map (thesis 5.6). Baked again unshrunk and
//     with maps grown over the whole city, the cell leaves it out.
//  5. pixel: the pixel size of the cull maps (thesis 7.2). Baked again unshrunk and with pixels
//     ExplainOptions::pixel_divisor times smaller (and the bake's own maps: maps over the whole
//     city at that pixel would be 16 times larger), the cell leaves it out.
//  6. occluder-model: none of the above. Hidden from every point tried and still kept by bakes
//     that relax ε, the far field and the pixel: the occluders are smaller than the surfaces
//     (roofs cut at the eaves, objects that cannot occlude, openings that the blocks keep), or
//     the samples are too sparse for occluders that are no longer shrunk.
// Steps 1 and 2 are the validator's own ray casting (RayScene), independent of the bake. Steps
// 3-5 re-bake the cell with the bake's code and the settings stored in the file; before that,
// the cell is baked with those settings as they are, and it must give the file's PVS exactly
// (the file was baked by this version from this city), or nothing is explained.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/validate/Validator.hpp"

namespace urbanpvs::explain {

enum class ExcessCause : std::uint8_t {
  SeenFiner,
  ElsewhereInCell,
  Epsilon,
  FarField,
  Pixel,
  OccluderModel,
};
inline constexpr std::size_t kExcessCauses = 6;
/// "seen-finer", "elsewhere-in-cell", "epsilon", "far-field", "pixel", "occluder-model".
const char* cause_name(ExcessCause cause);

struct ExplainOptions {
  /// The viewpoints and targets, as for urbanpvs-validate: the excess is that of its
  /// tightness viewpoints.
  validate::ValidationOptions validation;
  /// Target spacing of step 1, as a fraction of validation.point_spacing [Limit: 0.01 .. 1]
  double finer_spacing = 0.25;
  /// Random points of the prism tried in step 2, besides its top corners and top-edge
  /// middles [Limit: 0 .. 4096]
  std::size_t cell_viewpoints = 32;
  /// Pixels are this many times smaller in step 5 [Limit: 1 .. 16]
  int pixel_divisor = 4;
  /// Threads casting rays and baking cells again (the result does not depend on it)
  unsigned threads = 1;

  /// Throws std::invalid_argument naming the first value out of its limits.
  void validate() const;
};

/// One object of one viewpoint's excess.
struct ExcessObject {
  std::size_t viewpoint = 0;  ///< index among the tightness viewpoints
  std::uint32_t cell = 0;
  validate::Vec3 at;  ///< the viewpoint
  std::uint32_t object = 0;
  ExcessCause cause = ExcessCause::OccluderModel;
};

/// One tightness viewpoint: its cell, |PVS| and the number of objects seen from it.
struct ViewpointTally {
  std::uint32_t cell = 0;
  std::size_t pvs = 0, seen = 0;
};

struct ExcessBreakdown {
  validate::ValidationReport validation;   ///< misses and tightness, as urbanpvs-validate gives
  std::vector<ViewpointTally> viewpoints;  ///< the tightness viewpoints, in order
  std::vector<ExcessObject> objects;       ///< in viewpoint order, then object order
  std::array<std::size_t, kExcessCauses> counts{};  ///< objects per cause
  std::size_t cells_rebaked = 0;  ///< distinct cells baked again (each once per setting tried)

  std::size_t excess() const { return objects.size(); }
  /// What the mean tightness would be if the objects of `cause` left the PVS (and, for
  /// seen-finer, if they counted as seen instead).
  double tightness_without(ExcessCause cause) const;
};

/// Throws std::invalid_argument for options out of their limits or bake options the file does
/// not record, std::runtime_error when the file does not belong to the city (as validate) or
/// when a cell baked again with the file's settings differs from the file.
ExcessBreakdown explain_excess(const geometry::City& city, const runtime::PvsFile& pvs,
                               const preprocess::BakeOptions& bake, const ExplainOptions& options);

/// The bake options stored in a file's properties (preprocess::bake_options_from_properties).
preprocess::BakeOptions bake_options_of(const runtime::PvsFile& pvs);

}  // namespace urbanpvs::explain
