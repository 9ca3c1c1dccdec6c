// SPDX-License-Identifier: MIT
#pragma once

// Hand-written JSON output: string escaping and shortest round-trip numbers.

#include <string>
#include <string_view>

namespace urbanpvs::inspect {

/// `s` as a JSON string literal, quotes included. Control characters become \uXXXX (or their
/// short escapes); the strings of a valid .pvs file are already UTF-8, which JSON accepts as is.
std::string json_string(std::string_view s);

/// Shortest decimal that reads back as exactly `v` (std::to_chars), "null" if not finite.
std::string json_number(double v);

}  // namespace urbanpvs::inspect
