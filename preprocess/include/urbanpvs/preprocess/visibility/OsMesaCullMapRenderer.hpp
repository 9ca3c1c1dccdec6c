// SPDX-License-Identifier: GPL-3.0-or-later
// The OpenGL backend of the cell cull map (thesis 5.5), off screen through OSMesa (llvmpipe).
// Shadow heights go into the depth buffer of an orthographic top-down view; one sample's
// shadows merge by the depth test (max), and samples merge by the thesis's two-pass stencil
// method (min). It must agree with the CPU reference (cell_cull_map) within kDepthMargin.
#pragma once

#include <memory>
#include <span>

#include "urbanpvs/preprocess/visibility/CellCullMap.hpp"

namespace urbanpvs::preprocess {

class OsMesaCullMapRenderer {
 public:
  /// Creates an off-screen OpenGL 4.5 core context. One renderer per thread: the context is
  /// made current on the constructing thread and every call must come from it.
  /// Throws std::runtime_error when OSMesa cannot provide the context.
  OsMesaCullMapRenderer();
  ~OsMesaCullMapRenderer();
  OsMesaCullMapRenderer(const OsMesaCullMapRenderer&) = delete;
  OsMesaCullMapRenderer& operator=(const OsMesaCullMapRenderer&) = delete;

  /// Same result as cell_cull_map(grid, samples, occluders) up to the depth precision: heights
  /// are mapped linearly from [zlo, zhi] to depth [0, 1] (zlo must be below every object, it
  /// stands for "nothing hidden"; heights above zhi are clamped down, which is conservative),
  /// and every value read back is lowered by kDepthMargin·(zhi - zlo) so that it is never above
  /// the true height.
  CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                        std::span<const geometry::Occluder* const> occluders, double zlo,
                        double zhi, CullMapStats* stats = nullptr);
  CullMap cell_cull_map(const CullMapGrid& grid, std::span<const Vec3> samples,
                        std::span<const geometry::Occluder> occluders, double zlo, double zhi,
                        CullMapStats* stats = nullptr) {
    return cell_cull_map(grid, samples, pointers_to(occluders), zlo, zhi, stats);
  }

  /// Depth read back from llvmpipe was measured within ~2e-6 of the normalized range; four
  /// times that is subtracted.
  static constexpr double kDepthMargin = 8e-6;

 private:
  struct Context;
  std::unique_ptr<Context> gl_;
};

}  // namespace urbanpvs::preprocess
