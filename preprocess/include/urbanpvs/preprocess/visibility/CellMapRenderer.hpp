// SPDX-License-Identifier: GPL-3.0-or-later
// The two ways to compute a cell cull map (thesis 5.5) behind one interface, so that the
// hierarchical test (thesis 5.6) and the bake do not care which one runs: the exact CPU
// reference and the OpenGL (OSMesa) two-pass stencil merge. Both must agree within
// OsMesaCullMapRenderer::kDepthMargin.
#pragma once

#include <memory>
#include <span>

#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"

namespace urbanpvs::preprocess {

enum class Backend { Cpu, OsMesa };

class CellMapRenderer {
 public:
  virtual ~CellMapRenderer() = default;
  /// min over `samples` of max over the shadows of `occluders`, on `grid`.
  virtual CullMap render(const CullMapGrid& grid, std::span<const Vec3> samples,
                         std::span<const geometry::Occluder* const> occluders,
                         CullMapStats* stats) = 0;
};

/// One renderer per thread (the OpenGL one owns a context). Heights are expected in [zlo, zhi]:
/// zlo below every object, zhi above every occluder (only the OpenGL backend uses them, to map
/// heights to depth). `skipping` applies to the CPU renderer (OpenGL draws every occluder).
/// Throws std::runtime_error when the backend is not available.
std::unique_ptr<CellMapRenderer> make_cell_map_renderer(
    Backend backend, double zlo, double zhi,
    OccluderSkipping skipping = OccluderSkipping::HiddenInMap);

}  // namespace urbanpvs::preprocess
