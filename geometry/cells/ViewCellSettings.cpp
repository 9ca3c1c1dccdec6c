// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"

#include <filesystem>

namespace urbanpvs::geometry {

namespace {

// everywhere | streets | FILE: a name that is neither keyword is the region's file, the same as
// --region FILE.
Setting<ViewCellOptions> cells_setting() {
  using V = ViewCellOptions;
  auto s = choice_setting<V::Placement, V>(
      "cells", SettingStage::Cells, {"everywhere", "streets", "FILE"},
      "Cells go into all free space near the buildings, only onto the streets, squares and paths "
      "the input maps (OpenStreetMap highways by their width), or into the GeoJSON "
      "(Multi)Polygons of FILE (the city's CRS; as --region FILE)",
      [](V& v) -> V::Placement& { return v.placement; });
  s.get = [](const V& v) {
    switch (v.placement) {
      case V::Placement::Everywhere:
        return std::string("everywhere");
      case V::Placement::Streets:
        return std::string("streets");
      case V::Placement::File:
        break;
    }
    return v.region_file;
  };
  s.set = [key = s.key](V& v, const std::string& text) {
    v.region_file.clear();
    if (text == "everywhere") {
      v.placement = V::Placement::Everywhere;
    } else if (text == "streets") {
      v.placement = V::Placement::Streets;
    } else {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(text, ec))
        setting_detail::refuse(key, "must be everywhere, streets or an existing region file", text);
      v.placement = V::Placement::File;
      v.region_file = text;
    }
  };
  return s;
}

}  // namespace

const SettingTable<ViewCellOptions>& view_cell_settings() {
  using S = SettingStage;
  using V = ViewCellOptions;
  static const SettingTable<V> table = {
      cells_setting(),
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
