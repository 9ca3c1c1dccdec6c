// SPDX-License-Identifier: GPL-3.0-or-later
// The settings table of reading a city (ReadOptions): shared by every tool that reads one.
#pragma once

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/settings/Setting.hpp"

namespace urbanpvs::geometry {

const SettingTable<ReadOptions>& read_settings();

}  // namespace urbanpvs::geometry
