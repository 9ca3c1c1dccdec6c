// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/BlockSettings.hpp"

namespace urbanpvs::geometry {

const SettingTable<BlockOptions>& block_settings() {
  using S = SettingStage;
  using B = BlockOptions;
  static const SettingTable<B> table = {
      number_setting<B>("gap", "m", S::Occluders, 0, 10,
                        "Footprints closer than this fuse into one block, and into one obstacle "
                        "for the view cells",
                        [](B& b) -> double& { return b.gap_tolerance; }),
      number_setting<B>("height-step", "m", S::Occluders, 0, 100,
                        "Occluder tops are rounded down to a multiple of this (0: exact heights)",
                        [](B& b) -> double& { return b.height_step; }),
      number_setting<B>("outline-tolerance", "m", S::Occluders, 0, 0.05,
                        "Block outlines are simplified within this before shrinking, and shrunk "
                        "by as much more (0: every vertex kept)",
                        [](B& b) -> double& { return b.outline_tolerance; }),
      number_setting<B>(
          "terrain-step", "m", S::Occluders, 0, 1000,
          "The terrain occludes as levels this far apart (0: it hides nothing; 8 suits "
          "hilly cities whose buildings have heights)",
          [](B& b) -> double& { return b.terrain_step; }),
      number_setting<B>(
          "terrain-planes", "m", S::Occluders, 0, 1000,
          "The terrain occludes as sloped squares of this side, their tops under its slopes "
          "(0: off; experimental; 32 suits hilly cities whose buildings have heights)",
          [](B& b) -> double& { return b.terrain_planes; }),
      number_setting<B>(
          "solid-step", "m", S::Occluders, 0, 100,
          "Buildings that are not height fields (arcades, overhangs) are also shrunk in 3D "
          "(TetGen) into ground-standing levels this far apart (0: off; experimental; needs a "
          "build with URBANPVS_TETGEN=ON)",
          [](B& b) -> double& { return b.solid_step; }),
  };
  return table;
}

}  // namespace urbanpvs::geometry
