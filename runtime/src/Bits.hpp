// SPDX-License-Identifier: MIT
#pragma once

// Bit tricks the bitset and exp-Golomb PVS encodings need, without C++20's <bit>.

#include <cstdint>

/// Keeps a hot loop in its own function so its state gets registers of its own instead of
/// sharing (and spilling) them with the caller's.
#if defined(__GNUC__) || defined(__clang__)
#define URBANPVS_NOINLINE __attribute__((noinline))
#elif defined(_MSC_VER)
#define URBANPVS_NOINLINE __declspec(noinline)
#else
#define URBANPVS_NOINLINE
#endif

/// A hint to start loading the cache line at `address` (no effect where unsupported).
#if defined(__GNUC__) || defined(__clang__)
#define URBANPVS_PREFETCH(address) __builtin_prefetch(address)
#else
#define URBANPVS_PREFETCH(address) ((void)(address))
#endif

namespace urbanpvs::runtime::detail {

/// Index of the lowest set bit; `v` must be non-zero.
inline unsigned count_trailing_zeros64(std::uint64_t v) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  return static_cast<unsigned>(__builtin_ctzll(v));
#else
  unsigned n = 0;
  while ((v & 1u) == 0) {
    v >>= 1;
    ++n;
  }
  return n;
#endif
}

inline unsigned count_trailing_zeros(std::uint32_t v) noexcept {
  return count_trailing_zeros64(v);
}

/// Bits needed to write `v` (0 for 0).
inline unsigned bit_width64(std::uint64_t v) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  return v == 0 ? 0 : 64 - static_cast<unsigned>(__builtin_clzll(v));
#else
  unsigned n = 0;
  for (; v != 0; v >>= 1) ++n;
  return n;
#endif
}

/// Number of set bits of a byte.
inline unsigned popcount8(unsigned v) noexcept {
  v &= 0xFFu;
  v = v - ((v >> 1) & 0x55u);
  v = (v & 0x33u) + ((v >> 2) & 0x33u);
  return (v + (v >> 4)) & 0x0Fu;
}

}  // namespace urbanpvs::runtime::detail
