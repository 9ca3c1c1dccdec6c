// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table of the view-cell subdivision (ViewCellOptions; thesis 5.3). validate()
// checks options against it. The region is not in it: tools read it from a file of their own.
#pragma once

#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/geometry/settings/Setting.hpp"

namespace urbanpvs::geometry {

const SettingTable<ViewCellOptions>& view_cell_settings();

}  // namespace urbanpvs::geometry
