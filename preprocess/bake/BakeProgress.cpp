// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeProgress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace urbanpvs::preprocess {
namespace {

constexpr auto kBarInterval = std::chrono::milliseconds(250);
constexpr auto kLogInterval = std::chrono::seconds(5);
constexpr int kBarWidth = 30;

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--:--:--";
  const auto s = static_cast<unsigned long long>(seconds + 0.5);
  char text[32];
  std::snprintf(text, sizeof text, "%llu:%02llu:%02llu", s / 3600, s / 60 % 60, s % 60);
  return text;
}

}  // namespace

BakeProgress::Style BakeProgress::style_for(std::FILE* out, bool quiet) {
  if (quiet) return Style::Silent;
  return ::isatty(::fileno(out)) ? Style::Bar : Style::Log;
}

BakeProgress::BakeProgress(Style style, std::size_t total, std::size_t already_done, std::FILE* out,
                           std::string prefix)
    : style_(style),
      total_(total),
      already_done_(already_done),
      out_(out),
      prefix_(std::move(prefix)),
      start_(Clock::now()),
      last_print_(start_) {}

std::string BakeProgress::describe(std::size_t done, std::size_t total, double cells_per_second) {
  const double percent = total > 0 ? 100.0 * double(done) / double(total) : 100.0;
  const double eta = cells_per_second > 0 ? double(total - std::min(done, total)) / cells_per_second
                                          : (done >= total ? 0.0 : -1.0);
  char text[160];
  std::snprintf(text, sizeof text, "%zu/%zu cells (%.1f %%), %.1f cells/s, ETA %s", done, total,
                percent, cells_per_second, clock_text(eta).c_str());
  return text;
}

void BakeProgress::update(std::size_t computed) {
  if (style_ == Style::Silent) return;
  const auto now = Clock::now();
  if (now - last_print_ < (style_ == Style::Bar ? kBarInterval : kLogInterval)) return;
  last_print_ = now;
  print(computed, false);
}

void BakeProgress::finish(std::size_t computed) {
  if (style_ == Style::Bar || (style_ == Style::Log && printed_)) print(computed, true);
}

void BakeProgress::print(std::size_t computed, bool final) {
  const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
  const double rate = seconds > 0 ? double(computed) / seconds : 0.0;
  const std::size_t done = std::min(total_, already_done_ + computed);
  const std::string state = describe(done, total_, rate);
  if (style_ == Style::Bar) {
    const int filled =
        total_ > 0 ? static_cast<int>(kBarWidth * double(done) / double(total_)) : kBarWidth;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(kBarWidth, '.');
    // \033[K clears what a longer previous state left at the end of the line.
    std::fprintf(out_, "\r[%s] %s\033[K%s", bar.c_str(), state.c_str(), final ? "\n" : "");
  } else {
    std::fprintf(out_, "%s%s\n", prefix_.c_str(), state.c_str());
  }
  std::fflush(out_);
  printed_ = true;
}

}  // namespace urbanpvs::preprocess
