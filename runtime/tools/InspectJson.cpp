// SPDX-License-Identifier: MIT
// urbanpvs-inspect FILE --json: everything in the file, written by hand (no JSON library).
#include <cinttypes>
#include <cstdio>
#include <ostream>

#include "Inspect.hpp"
#include "JsonText.hpp"

namespace urbanpvs::inspect {
namespace {

void write_point_list(std::ostream& out, std::initializer_list<double> values) {
  out << '[';
  bool first = true;
  for (double v : values) {
    out << (first ? "" : ",") << json_number(v);
    first = false;
  }
  out << ']';
}

void write_header(const runtime::PvsFile& file, std::ostream& out) {
  const runtime::FrameInfo f = file.frame();
  const runtime::BakeSettings s = file.settings();
  out << "{\"format\":{\"major\":" << file.major_version() << ",\"minor\":" << file.minor_version()
      << "},\n\"coordinates\":" << json_string(reports_input_coordinates(file) ? "input" : "local")
      << ",\n\"frame\":{\"crs\":" << json_string(f.crs)
      << ",\"geographic\":" << (f.geographic ? "true" : "false") << ",\"geodetic_origin\":";
  write_point_list(out,
                   {f.geodetic_origin.lat_deg, f.geodetic_origin.lon_deg, f.geodetic_origin.h_m});
  out << ",\"origin\":";
  write_point_list(out, {f.origin[0], f.origin[1], f.origin[2]});
  char hash[32];
  std::snprintf(hash, sizeof hash, "%016" PRIx64, s.input_hash);
  out << "},\n\"settings\":{\"epsilon_m\":" << json_number(s.epsilon_m)
      << ",\"pixel_size_m\":" << json_number(s.pixel_size_m)
      << ",\"max_cell_edge_m\":" << json_number(s.max_cell_edge_m)
      << ",\"eye_min_m\":" << json_number(s.eye_min_m)
      << ",\"eye_max_m\":" << json_number(s.eye_max_m) << ",\"input_hash\":" << json_string(hash)
      << "},\n\"properties\":{";
  for (std::size_t i = 0; i < file.property_count(); ++i) {
    std::string_view key, value;
    file.property(i, key, value);
    out << (i ? "," : "") << json_string(key) << ':' << json_string(value);
  }
  out << "},\n";
}

void write_objects(const runtime::PvsFile& file, std::ostream& out) {
  out << "\"objects\":[";
  for (std::uint32_t i = 0; i < file.object_count(); ++i) {
    runtime::ObjectInfo o;
    file.object(i, o);
    const auto lo = reported(file, o.bbox[0], o.bbox[1], o.bbox[2]);
    const auto hi = reported(file, o.bbox[3], o.bbox[4], o.bbox[5]);
    out << (i ? ",\n" : "\n") << "{\"index\":" << i << ",\"id\":" << json_string(o.source_id);
    if (file.has_payloads()) out << ",\"payload\":" << json_string(o.payload);
    out << ",\"bbox\":";
    write_point_list(out, {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]});
    out << '}';
  }
  out << "],\n";
}

void write_cells(const runtime::PvsFile& file, std::ostream& out) {
  out << "\"cells\":[";
  runtime::PvsDecoder decoder(file);
  for (std::uint32_t i = 0; i < file.cell_count(); ++i) {
    runtime::CellGeometry c;
    file.cell(i, c);
    out << (i ? ",\n" : "\n") << "{\"index\":" << i << ",\"triangle\":[";
    for (int k = 0; k < 3; ++k) {
      const auto p = reported(file, c.triangle[k].x, c.triangle[k].y, 0);
      out << (k ? "," : "");
      write_point_list(out, {p[0], p[1]});
    }
    out << "],\"z\":";
    write_point_list(out, {reported(file, 0, 0, c.z_min)[2], reported(file, 0, 0, c.z_max)[2]});
    out << ",\"neighbours\":[";
    for (int k = 0; k < 3; ++k) {
      out << (k ? "," : "")
          << (c.neighbours[k] == runtime::kNoCell ? std::string("null")
                                                  : std::to_string(c.neighbours[k]));
    }
    out << "],\"pvs\":[";
    if (decoder.decode(i) == runtime::Status::kOk) {
      bool first = true;
      for (std::uint32_t object : decoder) {
        out << (first ? "" : ",") << object;
        first = false;
      }
    }
    out << "]}";
  }
  out << "]}\n";
}

}  // namespace

void write_json_dump(const runtime::PvsFile& file, std::ostream& out) {
  write_header(file, out);
  write_objects(file, out);
  write_cells(file, out);
}

}  // namespace urbanpvs::inspect
