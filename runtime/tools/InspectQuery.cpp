// SPDX-License-Identifier: MIT
// urbanpvs-inspect FILE --query: points in, one JSON line per point out.
#include <charconv>
#include <istream>
#include <ostream>

#include "Inspect.hpp"
#include "JsonText.hpp"

namespace urbanpvs::inspect {
namespace {

/// Three numbers separated by blanks (spaces, tabs, commas); locale-independent.
bool parse_point(const std::string& line, double (&v)[3]) {
  const char* p = line.data();
  const char* end = p + line.size();
  auto skip = [&] {
    while (p < end && (*p == ' ' || *p == '\t' || *p == ',' || *p == '\r')) ++p;
  };
  for (double& value : v) {
    skip();
    if (p < end && *p == '+') ++p;  // from_chars does not accept a leading '+'
    const auto result = std::from_chars(p, end, value);
    if (result.ec != std::errc()) return false;
    p = result.ptr;
  }
  skip();
  return p == end;
}

bool blank_or_comment(const std::string& line) {
  for (char c : line) {
    if (c == '#') return true;
    if (c != ' ' && c != '\t' && c != '\r') return false;
  }
  return true;
}

}  // namespace

int run_queries(const runtime::PvsFile& file, std::istream& points, bool geo, std::ostream& out,
                std::string& error) {
  runtime::PvsDecoder decoder(file);
  std::string line;
  for (std::size_t number = 1; std::getline(points, line); ++number) {
    if (blank_or_comment(line)) continue;
    double v[3];
    if (!parse_point(line, v)) {
      error = "line " + std::to_string(number) + ": expected three numbers, got '" + line + "'";
      return kExitBadQuery;
    }
    std::array<double, 3> local{};
    if (geo) {
      // lon lat h, as GIS tools write them.
      if (file.geodetic_to_local(v[1], v[0], v[2], local) != runtime::Status::kOk) {
        error = "line " + std::to_string(number) + ": the file is not geographic";
        return kExitBadQuery;
      }
    } else {
      local = file.input_to_local(v[0], v[1], v[2]);
    }
    const std::uint32_t cell = file.locate(local[0], local[1], local[2]);
    out << "{\"point\":[" << json_number(v[0]) << ',' << json_number(v[1]) << ','
        << json_number(v[2]) << "],\"local\":[" << json_number(local[0]) << ','
        << json_number(local[1]) << ',' << json_number(local[2]) << "],\"cell\":";
    if (cell == runtime::kNoCell) {
      out << "null,\"pvs\":[]}\n";
      continue;
    }
    out << cell << ",\"pvs\":[";
    if (decoder.decode(cell) == runtime::Status::kOk) {
      bool first = true;
      for (std::uint32_t object : decoder) {
        runtime::ObjectInfo info;
        file.object(object, info);
        out << (first ? "" : ",") << json_string(info.source_id);
        first = false;
      }
    }
    out << "]}\n";
  }
  return kExitOk;
}

}  // namespace urbanpvs::inspect
