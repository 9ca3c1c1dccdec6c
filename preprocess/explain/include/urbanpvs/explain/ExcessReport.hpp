// SPDX-License-Identifier: GPL-3.0-or-later
// The texts urbanpvs-explain writes from an ExcessBreakdown: the table of causes, and CSV files
// of the excess per object and per cell.
#pragma once

#include <string>

#include "urbanpvs/explain/ExcessBreakdown.hpp"

namespace urbanpvs::explain {

/// A Markdown table: per cause the objects, their share of the excess, their mean per
/// viewpoint and the tightness without them; then the totals.
std::string breakdown_table(const ExcessBreakdown& b);

/// One line per excess object: viewpoint,cell,x,y,z,object,source_id,cause (the viewpoint in
/// the file's local frame, m; source ids quoted as CSV requires).
std::string objects_csv(const ExcessBreakdown& b, const geometry::City& city);

/// One line per cell with a tightness viewpoint: cell,viewpoints,mean_pvs,mean_seen, then the
/// excess objects per cause (summed over the cell's viewpoints), cells in ascending order.
std::string cells_csv(const ExcessBreakdown& b);

}  // namespace urbanpvs::explain
