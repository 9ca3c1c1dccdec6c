// SPDX-License-Identifier: GPL-3.0-or-later
// The CPU reference rasterizer: writes an occluder shadow into a cull map at exactly the pixel
// centres it covers (OpenGL's sampling rule, half-open so shared edges are not counted twice),
// keeping the maximum (thesis 5.5: the umbra of one viewpoint is the union of its shadows).
#pragma once

#include "urbanpvs/preprocess/visibility/CullMap.hpp"
#include "urbanpvs/preprocess/visibility/OccluderShadow.hpp"

namespace urbanpvs::preprocess {

/// Pixels written (for statistics).
std::size_t rasterize_max(const OccluderShadow& shadow, CullMap& map);

}  // namespace urbanpvs::preprocess
