// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/explain/ExcessReport.hpp"

#include <cstdio>
#include <map>

namespace urbanpvs::explain {
namespace {

std::string format(const char* f, auto... values) {
  char text[256];
  std::snprintf(text, sizeof text, f, values...);
  return text;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (const char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

}  // namespace

std::string breakdown_table(const ExcessBreakdown& b) {
  const double viewpoints = static_cast<double>(std::max<std::size_t>(1, b.viewpoints.size()));
  const double excess = static_cast<double>(std::max<std::size_t>(1, b.excess()));
  std::string out =
      "| cause | objects | share | per viewpoint | tightness without it |\n"
      "|---|---|---|---|---|\n";
  for (std::size_t c = 0; c < kExcessCauses; ++c) {
    const auto cause = static_cast<ExcessCause>(c);
    out += format("| %s | %zu | %.1f%% | %.2f | %.3f |\n", cause_name(cause), b.counts[c],
                  100.0 * static_cast<double>(b.counts[c]) / excess,
                  static_cast<double>(b.counts[c]) / viewpoints, b.tightness_without(cause));
  }
  out += format("| all | %zu | 100%% | %.2f | 1.000 |\n", b.excess(),
                static_cast<double>(b.excess()) / viewpoints);
  out += format(
      "\n%zu viewpoints in %zu cells: mean |PVS| %.1f, mean seen %.1f, tightness %.3f; %zu "
      "cells baked again; misses: %zu\n",
      b.viewpoints.size(),
      [&] {
        std::map<std::uint32_t, int> cells;
        for (const ViewpointTally& v : b.viewpoints) cells[v.cell] = 1;
        return cells.size();
      }(),
      static_cast<double>(b.validation.pvs_total) / viewpoints,
      static_cast<double>(b.validation.seen_total) / viewpoints, b.validation.tightness(),
      b.cells_rebaked, b.validation.misses.size());
  return out;
}

std::string objects_csv(const ExcessBreakdown& b, const geometry::City& city) {
  std::string out = "viewpoint,cell,x,y,z,object,source_id,cause\n";
  for (const ExcessObject& e : b.objects)
    out +=
        format("%zu,%u,%.3f,%.3f,%.3f,%u,", e.viewpoint, e.cell, e.at.x, e.at.y, e.at.z, e.object) +
        csv_field(city.objects[e.object].source_id) + "," + cause_name(e.cause) + "\n";
  return out;
}

std::string cells_csv(const ExcessBreakdown& b) {
  struct Row {
    std::size_t viewpoints = 0, pvs = 0, seen = 0;
    std::array<std::size_t, kExcessCauses> counts{};
  };
  std::map<std::uint32_t, Row> rows;
  for (const ViewpointTally& v : b.viewpoints) {
    Row& r = rows[v.cell];
    ++r.viewpoints;
    r.pvs += v.pvs;
    r.seen += v.seen;
  }
  for (const ExcessObject& e : b.objects) ++rows[e.cell].counts[static_cast<std::size_t>(e.cause)];
  std::string out = "cell,viewpoints,mean_pvs,mean_seen";
  for (std::size_t c = 0; c < kExcessCauses; ++c)
    out += std::string(",") + cause_name(static_cast<ExcessCause>(c));
  out += "\n";
  for (const auto& [cell, r] : rows) {
    const double n = static_cast<double>(r.viewpoints);
    out += format("%u,%zu,%.2f,%.2f", cell, r.viewpoints, static_cast<double>(r.pvs) / n,
                  static_cast<double>(r.seen) / n);
    for (const std::size_t count : r.counts) out += format(",%zu", count);
    out += "\n";
  }
  return out;
}

}  // namespace urbanpvs::explain
