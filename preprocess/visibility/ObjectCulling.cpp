// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/ObjectCulling.hpp"

#include <cmath>

namespace urbanpvs::preprocess {

bool hidden_by(const CullMap& map, const geometry::Box3& box) {
  const CullMapGrid& g = map.grid();
  if (box.xy.empty()) return false;
  const auto [i0, j0, i1, j1] = g.touched(box.xy);
  if (i0 < 0 || j0 < 0 || i1 >= g.width || j1 >= g.height) return false;
  for (int j = static_cast<int>(j0); j <= static_cast<int>(j1); ++j)
    for (int i = static_cast<int>(i0); i <= static_cast<int>(i1); ++i)
      if (!(box.zmax < static_cast<double>(map.at(i, j)))) return false;
  return true;
}

std::vector<std::uint32_t> visible_objects(const CullMap& map,
                                           const std::vector<geometry::CityObject>& objects) {
  std::vector<std::uint32_t> out;
  for (const geometry::CityObject& o : objects)
    if (!hidden_by(map, o.bbox)) out.push_back(o.index);
  return out;
}

}  // namespace urbanpvs::preprocess
