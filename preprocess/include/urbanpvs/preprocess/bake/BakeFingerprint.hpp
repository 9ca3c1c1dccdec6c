// SPDX-License-Identifier: GPL-3.0-or-later
// Hashes that tie a bake to what it was made from: the input hash stored in the PVS file
// (BakeSettings::input_hash) and the fingerprint that decides whether a journal may be resumed.
// FNV-1a 64: no dependency, byte-order independent, fast enough (about 1 GB/s) next to parsing
// the same bytes; it guards against mix-ups, not against someone forging a collision.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace urbanpvs::preprocess {

/// Incremental 64-bit FNV-1a. Numbers are fed as little-endian bytes and strings with their
/// length first, so ("ab", "c") and ("a", "bc") hash differently.
class Fnv1a64 {
 public:
  void add_bytes(const void* data, std::size_t size);
  void add_u64(std::uint64_t value);
  void add_string(std::string_view text);
  std::uint64_t value() const { return state_; }

 private:
  std::uint64_t state_ = 0xcbf29ce484222325ull;
};

/// The input hash: FNV-1a over each file's length and the FNV-1a of its bytes, in order. Throws
/// geometry::InputError(Unreadable) naming the file that cannot be read.
std::uint64_t hash_input_files(const std::vector<std::string>& paths);

/// "0x" and 16 lower-case hex digits: how hashes appear in messages, reports and metadata.
std::string hex64(std::uint64_t value);

/// The identity of a bake's result: the input hash, every setting that changes the PVSs (as the
/// key/value strings stored in the file, so both name the same thing), and the scene's size.
/// Two runs with equal fingerprints compute identical cells, so their journals can be mixed.
std::uint64_t bake_fingerprint(std::uint64_t input_hash,
                               const std::vector<std::pair<std::string, std::string>>& settings,
                               std::size_t cells, std::size_t objects);

}  // namespace urbanpvs::preprocess
