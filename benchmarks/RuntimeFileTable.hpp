// SPDX-License-Identifier: MIT
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace urbanpvs::bench {

/// The cost of reading the clock twice (ns), the median of 2,000 empty timings: what each timed
/// query subtracts.
inline double timer_overhead_ns() {
  using Clock = std::chrono::steady_clock;
  std::vector<double> empty(2000);
  for (double& e : empty) {
    const auto t0 = Clock::now();
    const auto t1 = Clock::now();
    e = std::chrono::duration<double, std::nano>(t1 - t0).count();
  }
  std::nth_element(empty.begin(), empty.begin() + empty.size() / 2, empty.end());
  return empty[empty.size() / 2];
}

/// The table of `runtime_benchmark --files A.pvs ...` (RuntimeFileTable.cpp); argv are the files.
int run_file_table(int argc, char** argv);

}  // namespace urbanpvs::bench
