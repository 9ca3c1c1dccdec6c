// SPDX-License-Identifier: GPL-3.0-or-later
// Fuzzing read_city_text: whatever the bytes, the readers may only load a city or throw
// InputError; any other exception, a crash or a sanitizer report is a bug. A city that loads must
// keep the model's invariants (finite bboxes, valid counter-clockwise footprints, occluder tops
// not below their ground): a violation is reported like a crash.
//
// Built two ways from this one file:
//  - geometry_reader_fuzz (clang only): a libFuzzer target. For useful coverage configure a
//    separate build with the library instrumented too: configure with CXX=clang++,
//    CMAKE_BUILD_TYPE=RelWithDebInfo and
//    CMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined", build the target
//    geometry_reader_fuzz and run it on the seed folders tests/data/bad and tests/data/repairable.
//  - geometry_reader_fuzz_replay (any compiler, URBANPVS_FUZZ_REPLAY): a GoogleTest that feeds
//    every file of tests/data/bad and tests/data/repairable, and a fixed set of random mutations
//    of them, through the same entry point. Each input runs in a child process, so a crash is
//    reported with the input that caused it (saved under URBANPVS_FUZZ_ARTIFACTS) instead of
//    ending the run.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"

namespace {

using namespace urbanpvs::geometry;

// The options vary with the first byte, so every reading mode gets fuzzed.
ReadOptions options_for(std::string_view text) {
  ReadOptions o;
  const unsigned char k = text.empty() ? 0 : static_cast<unsigned char>(text.front());
  if (k & 1) o.default_height = 10.0;
  o.strict = (k & 2) != 0;
  o.coordinates = (k & 12) == 4   ? ReadOptions::Coordinates::Geographic
                  : (k & 12) == 8 ? ReadOptions::Coordinates::Projected
                                  : ReadOptions::Coordinates::Auto;
  return o;
}

bool finite_box(const Box3& b) {
  return !b.xy.empty() && b.zmin <= b.zmax && std::isfinite(b.xy.min.x) &&
         std::isfinite(b.xy.min.y) && std::isfinite(b.xy.max.x) && std::isfinite(b.xy.max.y) &&
         std::isfinite(b.zmin) && std::isfinite(b.zmax);
}

// Why a polygon handed to later stages is unusable, or "" (CityModel.hpp's invariant).
std::string polygon_problem(const Polygon& p) {
  for (Vec2 v : p.outer)
    if (!std::isfinite(v.x) || !std::isfinite(v.y)) return "non-finite vertex";
  if (p.outer.size() < 3) return "outer ring with < 3 points";
  if (signed_area2(p.outer) <= 0) return "outer ring not counter-clockwise";
  for (const Ring& h : p.holes)
    if (h.size() < 3 || signed_area2(h) >= 0) return "hole not clockwise";
  return polygon_defect(p);
}

// What every loaded city must satisfy; a violation is reported like a crash.
void check_city(const City& city) {
  auto fail = [](const std::string& id, const std::string& why) {
    throw std::logic_error("loaded city breaks an invariant: object " + id + ": " + why);
  };
  if (city.objects.empty()) fail("-", "no objects (should have been EmptyCity)");
  for (std::size_t i = 0; i < city.objects.size(); ++i) {
    const CityObject& o = city.objects[i];
    if (o.index != i) fail(o.source_id, "index out of order");
    if (o.source_id.empty()) fail("#" + std::to_string(i), "empty source_id");
    if (!finite_box(o.bbox)) fail(o.source_id, "empty or non-finite bbox");
    if (!std::isfinite(o.ground_z)) fail(o.source_id, "non-finite ground_z");
    for (const Polygon& p : o.footprint)
      if (std::string why = polygon_problem(p); !why.empty())
        fail(o.source_id, "footprint: " + why);
    for (const OccluderPrism& occ : o.occluders) {
      if (!std::isfinite(occ.ground_z) || !std::isfinite(occ.top_z) || occ.top_z < occ.ground_z)
        fail(o.source_id, "occluder with bad heights");
      if (std::string why = polygon_problem(occ.footprint); !why.empty())
        fail(o.source_id, "occluder: " + why);
    }
  }
}

// Reads `text`; returns normally on success or InputError, lets anything else escape.
void read_one(std::string_view text) {
  std::optional<City> city;
  try {
    city = read_city_text(text, "fuzz-input", options_for(text));
  } catch (const InputError&) {
    return;
  }
  check_city(*city);
}

}  // namespace

#ifndef URBANPVS_FUZZ_REPLAY

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  read_one(std::string_view(reinterpret_cast<const char*>(data), size));
  return 0;
}

#else  // the replay driver

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <typeinfo>
#include <vector>

namespace {

namespace fs = std::filesystem;

const fs::path kTestData = URBANPVS_TEST_DATA;
const fs::path kArtifacts = URBANPVS_FUZZ_ARTIFACTS;
constexpr int kMutations = 2000;

struct Input {
  std::string name;
  std::string text;
};

std::vector<Input> seed_inputs() {
  std::vector<Input> seeds;
  for (const char* dir : {"bad", "repairable"}) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(kTestData / dir))
      if (e.is_regular_file() && e.path().filename() != "EXPECTED.tsv") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& p : files) {
      std::ifstream in(p, std::ios::binary);
      std::ostringstream s;
      s << in.rdbuf();
      seeds.push_back({std::string(dir) + "/" + p.filename().string(), s.str()});
    }
  }
  return seeds;
}

// Byte- and token-level mutations that keep much of the JSON intact, so the readers get past
// the parser most of the time.
std::string mutate(std::string s, std::mt19937& rng) {
  static const std::vector<std::string> tokens{"{",
                                               "}",
                                               "[",
                                               "]",
                                               ",",
                                               ":",
                                               "\"",
                                               "0",
                                               "-1",
                                               "1e308",
                                               "1e-320",
                                               "-0",
                                               "null",
                                               "true",
                                               "false",
                                               "[]",
                                               "{}",
                                               "\"\"",
                                               "[0,0]",
                                               "[0]",
                                               "[[]]",
                                               "\"Building\"",
                                               "\"BuildingPart\"",
                                               "\"type\"",
                                               "\"Feature\"",
                                               "\"Polygon\"",
                                               "\"MultiPolygon\"",
                                               "\"RoofSurface\"",
                                               "\"children\"",
                                               "\"parents\"",
                                               "\"building:part\"",
                                               "4294967296",
                                               "2.5",
                                               "\"EPSG:4326\""};
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n)(rng); };
  const int rounds = 1 + static_cast<int>(pick(3));
  for (int r = 0; r < rounds; ++r) {
    if (s.empty()) s = "{}";
    const std::size_t at = pick(s.size() - 1);
    switch (pick(7)) {
      case 0:  // random byte
        s[at] = static_cast<char>(pick(255));
        break;
      case 1:  // delete a short run
        s.erase(at, 1 + pick(8));
        break;
      case 2:  // insert a token
        s.insert(at, tokens[pick(tokens.size() - 1)]);
        break;
      case 3: {  // replace the number or word at `at` by a token
        std::size_t end = at;
        while (end < s.size() &&
               (std::isalnum(static_cast<unsigned char>(s[end])) || s[end] == '.' || s[end] == '-'))
          ++end;
        s.replace(at, end - at, tokens[pick(tokens.size() - 1)]);
        break;
      }
      case 4: {  // duplicate a chunk somewhere else
        const std::string chunk = s.substr(at, 1 + pick(40));
        s.insert(pick(s.size()), chunk);
        break;
      }
      case 5:  // truncate
        s.resize(at);
        break;
      case 6: {  // swap two chunks' first characters (brackets and quotes)
        const std::size_t other = pick(s.size() - 1);
        std::swap(s[at], s[other]);
        break;
      }
      default: {  // change a digit
        for (std::size_t i = at; i < s.size(); ++i)
          if (std::isdigit(static_cast<unsigned char>(s[i]))) {
            s[i] = static_cast<char>('0' + pick(9));
            break;
          }
      }
    }
  }
  return s;
}

// Reads in a child process. Empty result: only a city or InputError; else what went wrong.
std::string run_isolated(const std::string& text) {
  std::fflush(nullptr);
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t pid = fork();
  if (pid < 0) return "fork failed";
  if (pid == 0) {
    close(fds[0]);
    std::string what;
    try {
      read_one(text);
    } catch (const std::exception& e) {
      what = std::string(typeid(e).name()) + ": " + e.what();
    } catch (...) {
      what = "an exception not derived from std::exception";
    }
    if (!what.empty()) {
      const ssize_t n = write(fds[1], what.data(), what.size());
      (void)n;
    }
    _exit(0);
  }
  close(fds[1]);
  std::string what;
  char buf[1024];
  for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) what.append(buf, buf + n);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFSIGNALED(status))
    return std::string("crashed: signal ") + std::to_string(WTERMSIG(status)) + " (" +
           strsignal(WTERMSIG(status)) + ")";
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    return "exited with status " + std::to_string(WEXITSTATUS(status));
  return what;
}

void check_all(const std::vector<Input>& inputs) {
  std::map<std::string, std::vector<std::string> > failures;  // what -> input names
  for (const Input& in : inputs) {
    const std::string what = run_isolated(in.text);
    if (what.empty()) continue;
    std::vector<std::string>& names = failures[what];
    names.push_back(in.name);
    if (names.size() <= 3) {
      fs::create_directories(kArtifacts);
      std::string file = in.name;
      for (char& c : file)
        if (c == '/') c = '_';
      std::ofstream(kArtifacts / file, std::ios::binary) << in.text;
    }
  }
  for (const auto& [what, names] : failures) {
    std::string list;
    for (std::size_t i = 0; i < names.size() && i < 5; ++i) list += " " + names[i];
    ADD_FAILURE() << names.size() << " input(s) escaped InputError: " << what << "\n  e.g." << list
                  << (names.size() > 5 ? " ..." : "") << "\n  (inputs saved under "
                  << kArtifacts.string() << ")";
  }
}

TEST(CityReaderFuzzReplay, SeedFilesRaiseOnlyInputError) {
  const std::vector<Input> seeds = seed_inputs();
  ASSERT_GE(seeds.size(), 24u);
  check_all(seeds);
}

TEST(CityReaderFuzzReplay, MutatedFilesRaiseOnlyInputError) {
  const std::vector<Input> seeds = seed_inputs();
  ASSERT_FALSE(seeds.empty());
  std::mt19937 rng(20240611);  // fixed: the same inputs on every run
  std::vector<Input> mutants;
  for (int i = 0; i < kMutations; ++i) {
    const Input& seed = seeds[static_cast<std::size_t>(i) % seeds.size()];
    mutants.push_back({seed.name + ".mutant" + std::to_string(i), mutate(seed.text, rng)});
  }
  check_all(mutants);
}

}  // namespace

#endif
