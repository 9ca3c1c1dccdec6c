// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/CityBake.hpp"

#include "urbanpvs/preprocess/bake/BakeSettings.hpp"

namespace urbanpvs::preprocess {

runtime::PvsBake bake_city(const geometry::City& city, const BakeOptions& options, BakeStats* stats,
                           const std::function<void(std::size_t, std::size_t)>& progress) {
  const BakeScene scene(city, options);
  CellVisibility visibility(scene);
  std::vector<std::vector<std::uint32_t>> pvs(scene.cell_count());
  BakeStats local;
  BakeStats& s = stats ? *stats : local;
  s.blocks = scene.blocks().size();
  s.occluders = scene.occluders().size();
  s.cells = scene.cell_count();
  for (std::uint32_t i = 0; i < scene.cell_count(); ++i) {
    pvs[i] = visibility.pvs(i, &s.counters);
    s.pvs_entries += pvs[i].size();
    if (progress) progress(i + 1, scene.cell_count());
  }
  for (const geometry::ViewCellMesh& mesh = scene.mesh(); const geometry::CellEdge& e : mesh.edges)
    s.samples += e.sample_count;
  return scene.pvs_file(std::move(pvs), bake_properties(options));
}

}  // namespace urbanpvs::preprocess
