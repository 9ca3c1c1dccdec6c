// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeReport.hpp"

#include <sys/resource.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "urbanpvs/preprocess/bake/BakeFingerprint.hpp"
#include "urbanpvs/preprocess/visibility/CellCounters.hpp"

namespace urbanpvs::preprocess {
namespace {

nlohmann::json typed(const std::string& text) {
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_number() || value.is_boolean()) return value;
  return text;
}

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace

std::string report_json(const BakeReport& r) {
  nlohmann::ordered_json j;
  j["tool"] = r.tool;
  nlohmann::ordered_json inputs = nlohmann::ordered_json::array();
  for (const InputFileInfo& f : r.inputs) inputs.push_back({{"path", f.path}, {"bytes", f.bytes}});
  j["inputs"] = inputs;
  j["input_hash"] = hex64(r.input_hash);
  j["fingerprint"] = hex64(r.fingerprint);
  j["output"] = {{"path", r.output}, {"bytes", r.output_bytes}};
  nlohmann::ordered_json settings = nlohmann::ordered_json::object();
  for (const auto& [key, value] : r.settings) settings[key] = typed(value);
  j["settings"] = settings;
  j["threads"] = r.threads;
  if (!r.ranks.empty()) {
    nlohmann::ordered_json ranks = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < r.ranks.size(); ++i)
      ranks.push_back({{"rank", i},
                       {"cells", r.ranks[i].cells},
                       {"threads", r.ranks[i].threads},
                       {"peak_memory_bytes", r.ranks[i].peak_bytes}});
    j["ranks"] = ranks;
    j["load_balance"] = r.load_balance();
  }
  j["counts"] = {{"objects", r.objects},
                 {"blocks", r.blocks},
                 {"occluders", r.occluders},
                 {"terrain_occluders", r.terrain_occluders},
                 {"solid_occluders", r.solid_occluders},
                 {"roof_plane_occluders", r.roof_plane_occluders},
                 {"solids_shrunk", r.solids_shrunk},
                 {"solids_declined", r.solids_declined},
                 {"cells", r.cells},
                 {"cell_area_m2", r.cell_area},
                 {"multipolygons", r.multipolygons},
                 {"cells_computed", r.cells_computed},
                 {"cells_from_journal", r.cells_from_journal},
                 {"pvs_entries", r.pvs_entries},
                 {"pvs_mean", r.mean_pvs()},
                 {"pvs_max", r.pvs_max},
                 {"fraction_culled", r.fraction_culled()},
                 {"bytes_per_cell", r.cells > 0 ? double(r.output_bytes) / double(r.cells) : 0.0}};
  j["repairs"] = r.repairs;
  j["non_occluding"] = r.non_occluding;
  j["warnings"] = r.warnings;
  j["terrain"] = r.terrain.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(r.terrain);
  j["seconds"] = {{"read", r.seconds.read},
                  {"scene", r.seconds.scene},
                  {"visibility", r.seconds.visibility},
                  {"write", r.seconds.write},
                  {"total", r.seconds.total()}};
  j["cells_per_second"] = r.cells_per_second();
  nlohmann::ordered_json counters = nlohmann::ordered_json::object();
  for (const auto& [name, member] : kCellCounterFields) counters[name] = r.counters.*member;
  j["counters"] = counters;
  j["peak_memory_bytes"] = r.peak_memory_bytes;
  return j.dump(2) + "\n";
}

std::string summary_text(const BakeReport& r) {
  std::string out;
  char line[512];
  auto add = [&](int n) {
    out.append(line, static_cast<std::size_t>(std::max(0, std::min(n, int(sizeof line) - 1))));
  };
  add(std::snprintf(line, sizeof line, "output:      %s (%llu bytes, %.1f per cell)\n",
                    r.output.c_str(), static_cast<unsigned long long>(r.output_bytes),
                    r.cells > 0 ? double(r.output_bytes) / double(r.cells) : 0.0));
  add(std::snprintf(line, sizeof line,
                    "cells:       %zu over %.3f km² (%zu computed on %u threads at %.1f cells/s, "
                    "%zu from the journal)\n",
                    r.cells, r.cell_area * 1e-6, r.cells_computed, r.threads, r.cells_per_second(),
                    r.cells_from_journal));
  if (!r.ranks.empty()) {
    std::string shares;
    std::uint64_t peak = 0;
    for (const RankShare& share : r.ranks) {
      shares += (shares.empty() ? "" : "/") + std::to_string(share.cells);
      peak = std::max(peak, share.peak_bytes);
    }
    add(std::snprintf(line, sizeof line,
                      "ranks:       %zu (cells %s; most over mean %.2f; peak per rank %s)\n",
                      r.ranks.size(), shares.c_str(), r.load_balance(), mib(peak).c_str()));
  }
  std::string terrain =
      r.terrain_occluders > 0 ? ", " + std::to_string(r.terrain_occluders) + " of the terrain" : "";
  if (r.roof_plane_occluders > 0)
    terrain += ", " + std::to_string(r.roof_plane_occluders) + " under sloped roof faces";
  add(std::snprintf(line, sizeof line, "objects:     %zu (%zu blocks, %zu occluders%s)\n",
                    r.objects, r.blocks, r.occluders, terrain.c_str()));
  if (r.solid_occluders > 0 || !r.solids_declined.empty()) {
    std::size_t declined = 0;
    for (const auto& [why, count] : r.solids_declined) declined += count;
    add(std::snprintf(line, sizeof line,
                      "solids:      %zu buildings that are not height fields shrunk in 3D into "
                      "%zu occluders, %zu gave none\n",
                      r.solids_shrunk, r.solid_occluders, declined));
    for (const auto& [why, count] : r.solids_declined)
      out += "  no solid:    " + std::to_string(count) + " buildings: " + why + "\n";
  }
  add(std::snprintf(line, sizeof line,
                    "input:       %zu geometric repairs, %zu objects that occlude nothing\n",
                    r.repairs.size(), r.non_occluding.size()));
  for (const std::string& text : r.repairs) out += "  repaired:    " + text + "\n";
  for (const std::string& text : r.non_occluding) out += "  no occluder: " + text + "\n";
  for (const std::string& text : r.warnings) out += "  warning:     " + text + "\n";
  if (r.multipolygons > 0)
    add(std::snprintf(line, sizeof line, "  OSM:         %zu buildings from multipolygons\n",
                      r.multipolygons));
  if (!r.terrain.empty()) out += "terrain:     " + r.terrain + "\n";
  add(std::snprintf(
      line, sizeof line, "PVS:         mean %.1f, max %llu objects; %.1f %% culled on average\n",
      r.mean_pvs(), static_cast<unsigned long long>(r.pvs_max), 100.0 * r.fraction_culled()));
  add(std::snprintf(line, sizeof line,
                    "time:        read %.2f s, scene %.2f s, visibility %.2f s, write %.2f s, "
                    "total %.2f s\n",
                    r.seconds.read, r.seconds.scene, r.seconds.visibility, r.seconds.write,
                    r.seconds.total()));
  add(std::snprintf(line, sizeof line, "memory:      peak %s\n", mib(r.peak_memory_bytes).c_str()));
  return out;
}

std::uint64_t peak_memory_bytes() {
  rusage usage{};
  if (::getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

}  // namespace urbanpvs::preprocess
