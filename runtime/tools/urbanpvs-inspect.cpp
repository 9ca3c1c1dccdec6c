// SPDX-License-Identifier: MIT
// urbanpvs-inspect: inspect a .pvs file (see --help). All logic lives in urbanpvs_inspect_lib.
#include <iostream>

#include "Inspect.hpp"

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  return urbanpvs::inspect::run(std::vector<std::string>(argv + 1, argv + argc), std::cin,
                                std::cout, std::cerr);
}
