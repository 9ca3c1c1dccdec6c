// SPDX-License-Identifier: MIT
// urbanpvs-inspect FILE: what the file is, how it was made, and how well the PVS compresses.
#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <ostream>

#include "Inspect.hpp"
#include "urbanpvs/runtime/Format.hpp"

namespace urbanpvs::inspect {
namespace {

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

struct PvsStats {
  std::uint32_t min = 0, max = 0;
  double mean = 0;
  std::uint32_t kinds[3] = {0, 0, 0};
  std::uint32_t max_chain = 0;
};

PvsStats pvs_stats(const runtime::PvsFile& file) {
  PvsStats s;
  const std::uint32_t n = file.cell_count();
  if (n == 0) return s;
  s.min = UINT32_MAX;
  for (std::uint32_t c = 0; c < n; ++c) {
    const std::uint32_t size = file.pvs_size(c);
    s.min = std::min(s.min, size);
    s.max = std::max(s.max, size);
    runtime::PvsEncodingInfo info;
    if (file.pvs_encoding(c, info) == runtime::Status::kOk && info.kind < 3) {
      ++s.kinds[info.kind];
      s.max_chain = std::max(s.max_chain, info.chain_length);
    }
  }
  s.mean = static_cast<double>(file.total_pvs_entries()) / n;
  return s;
}

}  // namespace

void write_summary(const runtime::PvsFile& file, const std::string& name, std::ostream& out) {
  const runtime::FrameInfo frame = file.frame();
  const runtime::BakeSettings settings = file.settings();
  out << "file:        " << name << " (" << file.file_size() << " bytes)\n";
  out << "format:      " << file.major_version() << "." << file.minor_version() << "\n";
  out << "frame:       CRS \"" << frame.crs << "\", "
      << (frame.geographic ? "geographic (WGS84) input" : "projected input") << "\n";
  if (frame.geographic) {
    out << "             ENU origin lat " << fmt("%.9f", frame.geodetic_origin.lat_deg) << " lon "
        << fmt("%.9f", frame.geodetic_origin.lon_deg) << " h "
        << fmt("%.3f", frame.geodetic_origin.h_m) << " m\n";
  }
  out << "             local origin (" << fmt("%.3f", frame.origin[0]) << ", "
      << fmt("%.3f", frame.origin[1]) << ", " << fmt("%.3f", frame.origin[2])
      << ") in input coordinates\n";
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016" PRIx64, settings.input_hash);
  out << "settings:    epsilon " << fmt("%g", settings.epsilon_m) << " m, pixel "
      << fmt("%g", settings.pixel_size_m) << " m, max cell edge "
      << fmt("%g", settings.max_cell_edge_m) << " m, eye band " << fmt("%g", settings.eye_min_m)
      << "-" << fmt("%g", settings.eye_max_m) << " m, input hash " << hash << "\n";
  for (std::size_t i = 0; i < file.property_count(); ++i) {
    std::string_view key, value;
    file.property(i, key, value);
    out << "property:    " << key << " = " << value << "\n";
  }
  const PvsStats s = pvs_stats(file);
  const std::uint32_t objects = file.object_count();
  const std::uint32_t cells = file.cell_count();
  out << "objects:     " << objects << "\n";
  if (file.has_payloads()) {
    std::uint32_t with = 0;
    for (std::uint32_t i = 0; i < objects; ++i) {
      runtime::ObjectInfo o;
      file.object(i, o);
      with += o.payload.empty() ? 0 : 1;
    }
    out << "payloads:    " << with << " of " << objects << " objects, from \"" << file.payload_key()
        << "\"\n";
  }
  out << "cells:       " << cells << "\n";
  out << "pvs size:    min " << s.min << ", mean " << fmt("%.1f", s.mean) << ", max " << s.max
      << "\n";
  out << "culled:      "
      << (objects > 0 ? fmt("%.2f %%", 100.0 * (1.0 - s.mean / objects)) : std::string("n/a"))
      << " (1 - mean |PVS| / objects)\n";
  out << "encoding:    " << s.kinds[0] << " delta lists, " << s.kinds[1] << " bitsets, "
      << s.kinds[2] << " diffs (longest chain " << s.max_chain << ")\n";
  out << "sections:\n";
  std::uint64_t pvs_bytes = 0;
  for (std::size_t i = 0; i < file.section_count(); ++i) {
    const runtime::SectionInfo sec = file.section(i);
    char line[96];
    std::snprintf(line, sizeof line, "  %-10s %12" PRIu64 " bytes\n",
                  runtime::format::section_name(sec.id), sec.length);
    out << line;
    if (sec.id == static_cast<std::uint32_t>(runtime::format::SectionId::kPvs))
      pvs_bytes = sec.length;
  }
  if (cells > 0) {
    const double plain = 4.0 * static_cast<double>(file.total_pvs_entries());
    out << "pvs bytes:   " << fmt("%.1f", static_cast<double>(pvs_bytes) / cells)
        << " per cell; plain 32-bit lists " << fmt("%.1f", plain / cells) << " per cell; ratio "
        << (plain > 0 ? fmt("%.3f", static_cast<double>(pvs_bytes) / plain) : std::string("n/a"))
        << "\n";
  }
}

}  // namespace urbanpvs::inspect
