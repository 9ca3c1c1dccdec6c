// SPDX-License-Identifier: MIT
#pragma once

// The bake behind tests/runtime/golden/v1_0.pvs. Changing it changes the golden file: the
// golden test compares the decoded file with values written out in the test itself, and the
// encoder's output with the committed bytes.

#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::test {

/// 6 cells (a strip of triangles) and 120 objects; the PVSs exercise every encoding: an empty
/// list, a delta list, a dense bitset, and diffs.
runtime::PvsBake golden_bake();

/// The options the golden file was encoded with. Explicit, so that tuning the writer's default
/// heuristics does not change the golden bytes (diff_threshold 1: cells 2 and 4 are diffs).
/// The options of the golden file of format `major` (tests/runtime/golden/v1_0.pvs, v2_0.pvs).
runtime::EncodeOptions golden_options(std::uint16_t major = 1);

}  // namespace urbanpvs::test
