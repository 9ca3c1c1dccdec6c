// SPDX-License-Identifier: GPL-3.0-or-later
// The order a bake works through its cells in. Neighbouring cells share samples (a sample on an
// edge belongs to the two cells beside it, a corner sample to about six) and leave nearly the
// same objects to the far field, whose answers per sample FarField keeps for a while. Cells
// taken along a Hilbert curve of their centroids come one after another with their neighbours,
// so those answers are still kept when the next cell asks. The order changes no PVS: only the
// time it takes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "urbanpvs/geometry/cells/ViewCells.hpp"

namespace urbanpvs::preprocess {

/// `cells` (indices into mesh.cells) sorted along a Hilbert curve over mesh.bounds, of the
/// centroid of each; ties by index. Deterministic.
std::vector<std::uint32_t> along_hilbert_curve(const geometry::ViewCellMesh& mesh,
                                               std::span<const std::uint32_t> cells);

}  // namespace urbanpvs::preprocess
