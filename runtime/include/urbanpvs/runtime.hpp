// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Umbrella header of the urbanpvs runtime (C++17, standard library only). See
/// urbanpvs/urbanpvs.h for the C API over the same functions.

#include "urbanpvs/runtime/crc32c.hpp"
#include "urbanpvs/runtime/file_io.hpp"
#include "urbanpvs/runtime/format.hpp"
#include "urbanpvs/runtime/geodetic_frame.hpp"
#include "urbanpvs/runtime/pvs_file.hpp"
#include "urbanpvs/runtime/pvs_writer.hpp"
#include "urbanpvs/runtime/status.hpp"
#include "urbanpvs/runtime/types.hpp"
