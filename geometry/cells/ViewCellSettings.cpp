// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"

namespace urbanpvs::geometry {

const SettingTable<ViewCellOptions>& view_cell_settings() {
  using S = SettingStage;
  using V = ViewCellOptions;
  static const SettingTable<V> table = {
      choice_setting<V::Placement, V>(
          "cells", S::Cells, {"everywhere", "streets"},
          "Without --region, cells go into all free space near the buildings, or only onto the "
          "streets, squares and paths the input maps (OpenStreetMap highways by their width)",
          [](V& v) -> V::Placement& { return v.placement; }),
      number_setting<V>("epsilon", "m", S::Cells, 0.01, 1000,
                        "Occluder shrinking and sample spacing epsilon (thesis 7.2)",
                        [](V& v) -> double& { return v.epsilon; }),
      number_setting<V>("max-cell-edge", "m", S::Cells, 0.5, 1e4, "Longest view-cell edge",
                        [](V& v) -> double& { return v.max_cell_edge; }),
      band_setting<V>(
          "eye-band", "m", S::Cells, 0, 1000, "Eye heights above the ground, MIN:MAX",
          [](V& v) -> double& { return v.eye_min; }, [](V& v) -> double& { return v.eye_max; }),
      number_setting<V>("margin", "m", S::Cells, 0, 1e5,
                        "Without --region, cells go within this distance of a building's "
                        "bounding rectangle",
                        [](V& v) -> double& { return v.margin; }),
      number_setting<V>("narrow-gap", "m", S::Cells, 0, 1,
                        "Slivers of free space thinner than this along a wall get no cells",
                        [](V& v) -> double& { return v.narrow_gap; }),
      number_setting<V>("snap", "m", S::Cells, 0, 10,
                        "Free space's boundary is cleaned within this (near-duplicate points, "
                        "walls closer than it); cells keep gap/2 + snap from every wall",
                        [](V& v) -> double& { return v.snap; }),
      number_setting<V>("min-cell-edge", "m", S::Cells, 0, 1e4,
                        "Cells and walls shorter than this are not refined for shape",
                        [](V& v) -> double& { return v.min_cell_edge; }),
      // The same key as the blocks' gap: a tool that makes both (the bake) binds the blocks'
      // one and hands its value on, so free space and blocks fuse the same footprints.
      number_setting<V>("gap", "m", S::Cells, 0, 10,
                        "Footprints closer than this fuse into one obstacle for the view cells",
                        [](V& v) -> double& { return v.gap; }),
  };
  return table;
}

}  // namespace urbanpvs::geometry
