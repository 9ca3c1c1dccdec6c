// SPDX-License-Identifier: GPL-3.0-or-later
// What a bake that runs for hours shows while it runs: on a terminal a progress bar redrawn in
// place (cells done, cells per second, ETA); in a log file or pipe a line every few seconds,
// since carriage returns would fill a log with thousands of bar states.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>

namespace urbanpvs::preprocess {

class BakeProgress {
 public:
  enum class Style { Bar, Log, Silent };
  /// Bar when `out` is a terminal, Log otherwise, Silent when `quiet`.
  static Style style_for(std::FILE* out, bool quiet);

  /// `total` cells, of which `already_done` came from a journal (they do not count for the
  /// speed). `prefix` starts every log line.
  BakeProgress(Style style, std::size_t total, std::size_t already_done, std::FILE* out,
               std::string prefix);

  /// `computed`: cells finished by this run so far. Prints only when the display is due.
  void update(std::size_t computed);
  /// Prints the final state; ends the bar's line.
  void finish(std::size_t computed);

  /// "1234/5000 cells (24.7 %), 85.3 cells/s, ETA 0:00:44": the state as one line.
  static std::string describe(std::size_t done, std::size_t total, double cells_per_second);

 private:
  void print(std::size_t computed, bool final);

  using Clock = std::chrono::steady_clock;
  Style style_;
  std::size_t total_, already_done_;
  std::FILE* out_;
  std::string prefix_;
  Clock::time_point start_, last_print_;
  bool printed_ = false;
};

}  // namespace urbanpvs::preprocess
