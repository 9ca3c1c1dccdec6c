// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), the checksum of every .pvs section.
/// Chosen over CRC-32 for its better error detection on the short bursts bit rot produces; a
/// table-driven slicing-by-8 implementation so a 10 MB file is verified in a few milliseconds.

#include <cstddef>
#include <cstdint>

namespace urbanpvs::runtime {

/// CRC-32C of `size` bytes at `data`. Pass the result of a previous call as `crc` to continue a
/// running checksum: crc32c(b, nb, crc32c(a, na)) == crc32c(a || b). `data` may be null when
/// `size` is 0. crc32c("123456789", 9) == 0xE3069283.
std::uint32_t crc32c(const void* data, std::size_t size, std::uint32_t crc = 0) noexcept;

}  // namespace urbanpvs::runtime
