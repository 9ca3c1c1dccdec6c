// SPDX-License-Identifier: MIT
// urbanpvs-inspect FILE --cell N: one cell in detail.
#include <cstdio>
#include <ostream>

#include "Inspect.hpp"

namespace urbanpvs::inspect {
namespace {

std::string point(double x, double y) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.3f, %.3f)", x, y);
  return buf;
}

const char* kind_name(std::uint8_t kind) {
  switch (kind) {
    case 0:
      return "delta list";
    case 1:
      return "bitset";
    default:
      return "diff";
  }
}

}  // namespace

bool write_cell_report(const runtime::PvsFile& file, std::uint32_t cell, std::ostream& out,
                       std::string& error) {
  runtime::CellGeometry c;
  if (file.cell(cell, c) != runtime::Status::kOk) {
    error = "cell " + std::to_string(cell) + " out of range";
    return false;
  }
  const char* frame = reports_input_coordinates(file) ? "input CRS" : "local frame";
  out << "cell " << cell << "\n  triangle (" << frame << "):";
  for (const runtime::Point2& p : c.triangle) {
    const auto r = reported(file, p.x, p.y, 0);
    out << " " << point(r[0], r[1]);
  }
  const auto lo = reported(file, 0, 0, c.z_min);
  const auto hi = reported(file, 0, 0, c.z_max);
  char z[96];
  std::snprintf(z, sizeof z, "[%.3f, %.3f]", lo[2], hi[2]);
  out << "\n  z range: " << z << "\n  neighbours:";
  for (std::uint32_t n : c.neighbours) {
    out << " " << (n == runtime::kNoCell ? std::string("none") : std::to_string(n));
  }
  runtime::PvsEncodingInfo info;
  if (file.pvs_encoding(cell, info) == runtime::Status::kOk) {
    out << "\n  encoding: " << kind_name(info.kind);
    if (info.reference != runtime::kNoCell) {
      out << " against cell " << info.reference << " (chain " << info.chain_length << ")";
    }
    out << ", " << info.payload_bytes << " bytes";
  }
  runtime::PvsDecoder decoder(file);
  if (decoder.decode(cell) != runtime::Status::kOk) {
    error = "cannot decode the PVS of cell " + std::to_string(cell);
    return false;
  }
  out << "\n  pvs: " << decoder.size() << " of " << file.object_count() << " objects\n";
  for (std::uint32_t object : decoder) {
    runtime::ObjectInfo info_object;
    file.object(object, info_object);
    out << "    " << object << "\t" << info_object.source_id;
    if (!info_object.payload.empty()) out << "\t" << info_object.payload;
    out << "\n";
  }
  return true;
}

}  // namespace urbanpvs::inspect
