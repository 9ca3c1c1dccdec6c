// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table of fusing buildings into blocks (BlockOptions; thesis 7).
#pragma once

#include "urbanpvs/geometry/occluders/Blocks.hpp"
#include "urbanpvs/geometry/settings/Setting.hpp"

namespace urbanpvs::geometry {

const SettingTable<BlockOptions>& block_settings();

}  // namespace urbanpvs::geometry
