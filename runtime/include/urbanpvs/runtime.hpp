// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// Umbrella header of the urbanpvs runtime (C++17, standard library only). See
/// urbanpvs/urbanpvs.h for the C API over the same functions.

#include "urbanpvs/runtime/Crc32c.hpp"
#include "urbanpvs/runtime/FileIo.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/GeodeticFrame.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"
#include "urbanpvs/runtime/Status.hpp"
#include "urbanpvs/runtime/Types.hpp"
