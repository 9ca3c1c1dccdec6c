// Deterministic pseudo-random numbers for the city generator.
//
// The generator promises identical bytes for identical parameters on every platform, so it cannot
// use std::uniform_*_distribution (their algorithms are implementation-defined) nor std::mt19937
// seeded through seed_seq. SplitMix64 is tiny, fast, passes BigCrush, and its output is fully
// specified by integer arithmetic; the mapping to doubles below uses only exact operations.
#pragma once

#include <cstdint>

namespace urbanpvs::cities {

/// SplitMix64 generator with exact, portable mappings to integers, doubles and booleans.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}

  /// An independent generator for one purpose ("stream") and one item of that purpose (e.g. a
  /// block index). Deriving streams instead of sharing one generator keeps a block's buildings
  /// stable when an unrelated part of the generator draws one more number.
  static Random forStream(std::uint64_t seed, std::uint64_t stream, std::uint64_t index = 0) {
    return Random(
        mix(seed ^ mix(stream * 0x9E3779B97F4A7C15ull + mix(index + 0x632BE59BD9B4E019ull))));
  }

  /// Next 64 random bits.
  std::uint64_t nextU64() {
    state_ += 0x9E3779B97F4A7C15ull;
    return mix(state_);
  }

  /// Uniform double in [0, 1): the top 53 bits scaled by 2^-53, which is exact.
  double uniform01() { return static_cast<double>(nextU64() >> 11) * 0x1.0p-53; }

  /// Uniform double in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }

  /// Uniform integer in [0, n) for n >= 1 (multiply-shift; the bias of < 2^-32 is irrelevant here
  /// and, unlike rejection sampling, the number of draws is fixed).
  std::uint32_t below(std::uint32_t n) {
    return static_cast<std::uint32_t>(((nextU64() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
  }

  /// True with probability p.
  bool chance(double p) { return uniform01() < p; }

  /// The SplitMix64 finaliser: a bijective 64-bit mixer.
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

}  // namespace urbanpvs::cities
