// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The exit codes of every urbanpvs command-line tool, defined once (README, "Exit codes"), so
/// that a script can tell a broken input from a broken command line whichever tool it runs.
/// Header only and dependency-free like the rest of the runtime, which every tool can include.

#include "urbanpvs/runtime/Status.hpp"

namespace urbanpvs::exit_code {

inline constexpr int kOk = 0;
inline constexpr int kMisses = 1;    ///< urbanpvs-validate: the PVS misses visible objects
inline constexpr int kUsage = 2;     ///< bad command line, config or option value; journal refused
inline constexpr int kBadQuery = 3;  ///< urbanpvs-inspect: a cell or point the file does not hold
inline constexpr int kProcessing = 4;  ///< the work itself failed (out of memory included)
inline constexpr int kOutput = 5;  ///< an output cannot be written; nothing half-written is left

/// 10-19: a city input file (geometry::InputProblem, whose values are these codes).
inline constexpr int kCityInputFirst = 10;
inline constexpr int kCityInputLast = 19;

inline constexpr int kFileUnreadable = 20;  ///< another input (a .pvs, a points file) unreadable
inline constexpr int kNotPvs = 21;          ///< not a .pvs file (bad magic)
inline constexpr int kPvsUnsupported = 22;  ///< newer major version or unknown required feature
inline constexpr int kPvsCorrupt = 23;      ///< truncated, trailing bytes, checksum, malformed

/// The exit code for a .pvs file that PvsFile::open_file refused.
constexpr int for_load(runtime::Status status) {
  switch (status) {
    case runtime::Status::kOk:
      return kOk;
    case runtime::Status::kIoError:
    case runtime::Status::kInvalidArgument:
      return kFileUnreadable;
    case runtime::Status::kBadMagic:
      return kNotPvs;
    case runtime::Status::kUnsupportedVersion:
    case runtime::Status::kUnsupportedFeature:
      return kPvsUnsupported;
    case runtime::Status::kOutOfMemory:
      return kProcessing;
    default:
      return kPvsCorrupt;
  }
}

}  // namespace urbanpvs::exit_code
