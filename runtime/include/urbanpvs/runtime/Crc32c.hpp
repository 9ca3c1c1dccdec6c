// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// CRC-32C (Castagnoli, reflected polynomial 0x82F63B78), the checksum of every .pvs section.
/// Chosen over CRC-32 for its better error detection on the short bursts bit rot produces, and
/// because x86-64 computes it in hardware (SSE4.2 `crc32`, chosen at run time: several GB/s);
/// elsewhere a table-driven slicing-by-8 implementation (about 1 GB/s).

#include <cstddef>
#include <cstdint>

namespace urbanpvs::runtime {

/// CRC-32C of `size` bytes at `data`. Pass the result of a previous call as `crc` to continue a
/// running checksum: crc32c(b, nb, crc32c(a, na)) == crc32c(a || b). `data` may be null when
/// `size` is 0. crc32c("123456789", 9) == 0xE3069283.
std::uint32_t crc32c(const void* data, std::size_t size, std::uint32_t crc = 0) noexcept;

namespace detail {
/// The table-driven implementation crc32c() falls back to (exposed so tests check both paths).
std::uint32_t crc32c_portable(const void* data, std::size_t size, std::uint32_t crc = 0) noexcept;
/// Whether crc32c() uses the CPU's CRC-32C instruction on this machine.
bool crc32c_is_hardware() noexcept;
}  // namespace detail

}  // namespace urbanpvs::runtime
