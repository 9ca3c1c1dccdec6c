// SPDX-License-Identifier: MIT
#include "urbanpvs/runtime/Crc32c.hpp"

#include <array>

#include "ByteReader.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <nmmintrin.h>
#define URBANPVS_CRC32C_X86 1
#endif

namespace urbanpvs::runtime {
namespace {

constexpr std::uint32_t kPolynomial = 0x82F63B78u;  // Castagnoli, bit-reversed

using Tables = std::array<std::array<std::uint32_t, 256>, 8>;

// Slicing-by-8: table[k][b] is the CRC of byte b followed by k zero bytes, so eight input bytes
// are folded with eight independent lookups per step instead of eight dependent ones.
constexpr Tables make_tables() {
  Tables t{};
  for (std::uint32_t b = 0; b < 256; ++b) {
    std::uint32_t crc = b;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ ((crc & 1u) ? kPolynomial : 0u);
    t[0][b] = crc;
  }
  for (std::size_t k = 1; k < 8; ++k) {
    for (std::size_t b = 0; b < 256; ++b) {
      t[k][b] = (t[k - 1][b] >> 8) ^ t[0][t[k - 1][b] & 0xFFu];
    }
  }
  return t;
}

constexpr Tables kTables = make_tables();

#if URBANPVS_CRC32C_X86
// SSE4.2's crc32 instruction computes exactly this CRC (it was added for iSCSI's CRC-32C): one
// 8-byte step per instruction, about 5x the tables' speed, which the 1 GB/s load target needs.
// Chosen at run time, so the library still runs on an x86-64 CPU without SSE4.2.
__attribute__((target("sse4.2"))) std::uint32_t crc32c_sse42(const unsigned char* p,
                                                             std::size_t size,
                                                             std::uint32_t c) noexcept {
  std::uint64_t c64 = c;
  while (size >= 8) {
    c64 = _mm_crc32_u64(c64, detail::load_u64(p));
    p += 8;
    size -= 8;
  }
  auto c32 = static_cast<std::uint32_t>(c64);
  while (size-- > 0) c32 = _mm_crc32_u8(c32, *p++);
  return c32;
}

bool has_sse42() noexcept {
  static const bool supported = __builtin_cpu_supports("sse4.2") != 0;
  return supported;
}
#endif

}  // namespace

namespace detail {

std::uint32_t crc32c_portable(const void* data, std::size_t size, std::uint32_t crc) noexcept {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint32_t c = ~crc;
  while (size >= 8) {
    const std::uint32_t lo = load_u32(p) ^ c;
    const std::uint32_t hi = load_u32(p + 4);
    c = kTables[7][lo & 0xFF] ^ kTables[6][(lo >> 8) & 0xFF] ^ kTables[5][(lo >> 16) & 0xFF] ^
        kTables[4][lo >> 24] ^ kTables[3][hi & 0xFF] ^ kTables[2][(hi >> 8) & 0xFF] ^
        kTables[1][(hi >> 16) & 0xFF] ^ kTables[0][hi >> 24];
    p += 8;
    size -= 8;
  }
  while (size-- > 0) c = (c >> 8) ^ kTables[0][(c ^ *p++) & 0xFF];
  return ~c;
}

bool crc32c_is_hardware() noexcept {
#if URBANPVS_CRC32C_X86
  return has_sse42();
#else
  return false;
#endif
}

}  // namespace detail

std::uint32_t crc32c(const void* data, std::size_t size, std::uint32_t crc) noexcept {
#if URBANPVS_CRC32C_X86
  if (size > 0 && has_sse42()) {
    return ~crc32c_sse42(static_cast<const unsigned char*>(data), size, ~crc);
  }
#endif
  return detail::crc32c_portable(data, size, crc);
}

}  // namespace urbanpvs::runtime
