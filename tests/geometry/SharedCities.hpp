// SPDX-License-Identifier: GPL-3.0-or-later
// The real city extracts of ../shared/cities (URBANPVS_SHARED_CITIES), which are never copied
// into the project: a test that needs one skips, saying so, when it is absent.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace urbanpvs::test {

inline const std::filesystem::path kSharedCities = URBANPVS_SHARED_CITIES;

}  // namespace urbanpvs::test

#define REQUIRE_SHARED_CITY(var, name)                                            \
  const std::string var = (urbanpvs::test::kSharedCities / (name)).string();      \
  if (!std::filesystem::is_regular_file(var))                                     \
  GTEST_SKIP() << var                                                             \
               << " is absent (real city extracts live in ../shared/cities; set " \
                  "URBANPVS_SHARED_CITIES)"
