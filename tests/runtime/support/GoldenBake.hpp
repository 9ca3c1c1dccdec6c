// SPDX-License-Identifier: MIT
#pragma once

// The bake behind tests/runtime/golden/v1_0.pvs, v2_0.pvs and v2_1.pvs. Changing it changes the
// golden file: the golden test compares the decoded file with values written out in the test
// itself, and the encoder's output with the committed bytes.

#include <cstdint>
#include <string>

#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::test {

/// 6 cells (a strip of triangles) and 120 objects; the PVSs exercise every encoding: an empty
/// list, a delta list, a dense bitset, and diffs.
runtime::PvsBake golden_bake();

/// golden_bake() with a payload per object (key "tile"; every third object none, one value
/// with non-ASCII text): the content of v2_1.pvs.
runtime::PvsBake golden_bake_with_payloads();
/// The payload golden_bake_with_payloads() gives object `object`.
std::string golden_payload(std::uint32_t object);

/// The options the golden files of format `major`.`minor` were encoded with. Explicit, so that
/// tuning the writer's default heuristics does not change the golden bytes (diff_threshold 1:
/// cells 2 and 4 are diffs). Minor 2 codes the PVS with exp-Golomb gaps; the others with varints.
runtime::EncodeOptions golden_options(std::uint16_t major = 1, std::uint16_t minor = 0);

}  // namespace urbanpvs::test
