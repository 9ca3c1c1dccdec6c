// SPDX-License-Identifier: MIT
// Standalone driver for LoaderFuzz.cpp where libFuzzer is not available (gcc): replays the
// seed corpus, then feeds random mutations of it (bit flips, interesting values, truncation,
// insertion, deletion, chunk copies) to the same entry point. Deterministic for a given seed.
//
//   urbanpvs_fuzz_loader [--mutations N] [--seed S] CORPUS_DIR_OR_FILE...
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Input = std::vector<std::uint8_t>;

Input read(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Input((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void mutate_once(Input& in, std::mt19937_64& rng) {
  static constexpr std::uint32_t kInteresting[] = {
      0, 1, 2, 0x7F, 0x80, 0xFF, 0x7FFFFFFF, 0x80000000u, 0xFFFFFFFFu, 0xFFFFFFFEu};
  auto pick = [&](std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(rng() % n); };
  switch (rng() % 7) {
    case 0:  // flip a bit
      if (!in.empty()) in[pick(in.size())] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
      break;
    case 1:  // an interesting byte
      if (!in.empty()) in[pick(in.size())] = static_cast<std::uint8_t>(kInteresting[rng() % 10]);
      break;
    case 2:  // an interesting little-endian u32 (counts, offsets, lengths)
      if (in.size() >= 4) {
        const std::size_t at = pick(in.size() - 3);
        const std::uint32_t v = kInteresting[rng() % 10];
        for (int i = 0; i < 4; ++i) in[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
      }
      break;
    case 3:  // truncate
      in.resize(pick(in.size() + 1));
      break;
    case 4: {  // insert random bytes
      const std::size_t at = pick(in.size() + 1);
      Input extra(1 + rng() % 16);
      for (auto& b : extra) b = static_cast<std::uint8_t>(rng());
      in.insert(in.begin() + static_cast<long>(at), extra.begin(), extra.end());
      break;
    }
    case 5:  // delete a range
      if (!in.empty()) {
        const std::size_t at = pick(in.size());
        const std::size_t n = 1 + pick(std::min<std::size_t>(32, in.size() - at));
        in.erase(in.begin() + static_cast<long>(at), in.begin() + static_cast<long>(at + n));
      }
      break;
    default:  // copy a chunk over another place
      if (in.size() >= 16) {
        const std::size_t n = 1 + pick(16);
        const std::size_t from = pick(in.size() - n), to = pick(in.size() - n);
        std::copy(in.begin() + static_cast<long>(from), in.begin() + static_cast<long>(from + n),
                  in.begin() + static_cast<long>(to));
      }
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t mutations = 2000;
  std::uint64_t seed = 1;
  std::vector<Input> corpus;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--mutations" && i + 1 < argc) {
      mutations = std::strtoull(argv[++i], nullptr, 10);
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::filesystem::is_directory(arg)) {
      for (const auto& entry : std::filesystem::directory_iterator(arg)) {
        if (entry.is_regular_file()) corpus.push_back(read(entry.path()));
      }
    } else {
      corpus.push_back(read(arg));
    }
  }
  if (corpus.empty()) {
    std::fprintf(stderr, "usage: %s [--mutations N] [--seed S] CORPUS...\n", argv[0]);
    return 2;
  }
  for (const Input& in : corpus) LLVMFuzzerTestOneInput(in.data(), in.size());
  std::mt19937_64 rng(seed);
  for (std::size_t m = 0; m < mutations; ++m) {
    Input in = corpus[rng() % corpus.size()];
    const int steps = 1 + static_cast<int>(rng() % 4);
    for (int s = 0; s < steps; ++s) mutate_once(in, rng);
    LLVMFuzzerTestOneInput(in.data(), in.size());
  }
  std::printf("replayed %zu corpus inputs and %zu mutations\n", corpus.size(), mutations);
  return 0;
}
