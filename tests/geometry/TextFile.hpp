// SPDX-License-Identifier: GPL-3.0-or-later
// A test's input file as one string (empty when it cannot be read; the test then fails on it).
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace urbanpvs::test {

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace urbanpvs::test
