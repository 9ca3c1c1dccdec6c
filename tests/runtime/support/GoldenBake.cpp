// SPDX-License-Identifier: MIT
#include "GoldenBake.hpp"

#include <string>

namespace urbanpvs::test {

using runtime::kNoCell;

runtime::EncodeOptions golden_options(std::uint16_t major, std::uint16_t minor) {
  runtime::EncodeOptions options;
  options.format_major = major;
  options.pvs_coding = minor == 2 ? runtime::PvsCoding::kExpGolomb : runtime::PvsCoding::kVarint;
  options.bbox_float32 = true;
  options.max_diff_chain = 1;
  options.diff_threshold = 1.0;
  options.grid_cells_per_cell = 1.0;
  return options;
}

runtime::PvsBake golden_bake() {
  runtime::PvsBake bake;
  bake.meta.frame.crs = "EPSG:7415";
  bake.meta.frame.geographic = false;
  bake.meta.frame.origin = {85000.0, 446000.0, -1.5};
  bake.meta.settings = {0.25, 0.5, 10.0, 1.5, 2.0, 0x0123456789ABCDEFULL};
  bake.meta.properties = {{"city", "Delft \"centrum\""}, {"note", "caf\xC3\xA9\n\ttab"}};
  // Objects: 120 boxes on a 12 x 10 grid, 8 m apart; bounds exactly representable in float32.
  for (int i = 0; i < 120; ++i) {
    const double x = (i % 12) * 8.0 - 4.0;
    const double y = (i / 12) * 8.0 + 12.0;
    bake.objects.push_back({"NL.IMBAG.Pand." + std::to_string(1000 + i),
                            {x, y, 0.0, x + 5.5, y + 4.25, 6.0 + (i % 7)},
                            {}});
  }
  // Cells: a strip of 6 triangles over [0, 30] x [0, 10], counter-clockwise; neighbour k is
  // across the edge from vertex k to vertex k + 1.
  const double zlo = 1.5, zhi = 2.0;
  bake.cells = {
      {{{{0, 0}, {10, 0}, {0, 10}}}, zlo, zhi, {kNoCell, 1, kNoCell}, {}},
      {{{{10, 0}, {10, 10}, {0, 10}}}, zlo, zhi, {2, kNoCell, 0}, {}},
      {{{{10, 0}, {20, 0}, {10, 10}}}, zlo, zhi + 1, {kNoCell, 3, 1}, {}},
      {{{{20, 0}, {20, 10}, {10, 10}}}, zlo, zhi, {4, kNoCell, 2}, {}},
      {{{{20, 0}, {30, 0}, {20, 10}}}, zlo, zhi, {kNoCell, 5, 3}, {}},
      {{{{30, 0}, {30, 10}, {20, 10}}}, zlo - 1, zhi, {kNoCell, kNoCell, 4}, {}},
  };
  bake.cells[0].pvs = {};                                         // nothing visible
  bake.cells[1].pvs = {0, 13, 27, 41, 55, 69, 83, 97, 111, 119};  // sparse: delta list
  bake.cells[2].pvs = {0, 3, 13, 27, 41, 55, 69, 83, 97, 111};    // diff against 1: -119 +3
  for (std::uint32_t i = 0; i < 120; ++i) {
    if (i % 5 != 4) bake.cells[3].pvs.push_back(i);  // dense: bitset
  }
  bake.cells[4].pvs.assign(bake.cells[3].pvs.begin() + 1, bake.cells[3].pvs.end());  // diff: -0
  bake.cells[5].pvs = {7, 38};
  return bake;
}

std::string golden_payload(std::uint32_t object) {
  if (object == 23) return "caf\xC3\xA9/23";
  if (object % 3 == 2) return {};
  return "tiles/" + std::to_string(object / 12) + "/" + std::to_string(object % 12) + ".glb";
}

runtime::PvsBake golden_bake_with_payloads() {
  runtime::PvsBake bake = golden_bake();
  bake.payload_key = "tile";
  for (std::uint32_t i = 0; i < bake.objects.size(); ++i)
    bake.objects[i].payload = golden_payload(i);
  return bake;
}

}  // namespace urbanpvs::test
