// SPDX-License-Identifier: GPL-3.0-or-later
// Where people can be, from OpenStreetMap (read_osm's kStreetsMember): highway lines in the
// local frame with their widths (width, else lanes, else a width per highway class), and
// street areas repaired like footprints. The view cells buffer and fuse them only when asked to
// (--cells streets; cells/StreetRegion.cpp).
#include <cmath>
#include <cstring>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"

namespace urbanpvs::geometry::detail {
namespace {

// Width of one lane where a way gives `lanes` but no width.
constexpr double kLaneWidth = 3.0;  // m

// Carriageway plus the space beside it where people walk, by highway class, where the way
// gives neither width nor lanes. [m]
double class_width(const std::string& highway) {
  struct Entry {
    const char* name;
    double width;
  };
  static constexpr Entry kWidths[] = {
      {"motorway", 16},     {"trunk", 14},       {"primary", 12},     {"secondary", 11},
      {"tertiary", 10},     {"unclassified", 8}, {"residential", 8},  {"living_street", 7},
      {"pedestrian", 8},    {"service", 5},      {"track", 4},        {"cycleway", 3},
      {"footway", 3},       {"path", 2},         {"steps", 3},        {"bridleway", 3},
      {"motorway_link", 8}, {"trunk_link", 8},   {"primary_link", 8}, {"secondary_link", 7},
      {"tertiary_link", 7}, {"corridor", 2},     {"busway", 8},       {"road", 6}};
  for (const Entry& e : kWidths)
    if (highway == e.name) return e.width;
  return 4;
}

double street_width(const Json& s, const std::string& file, ReadReport& report) {
  for (const char* key : {"width", "est_width"})
    if (s.contains(key)) {
      if (std::optional<double> w = parse_length(s[key]); w && *w > 0 && *w < 200) return *w;
      report.warnings.push_back(file + ": " + s["id"].get<std::string>() + ": cannot read " + key +
                                " " + s[key].dump() + "; the highway class's width is used");
    }
  if (s.contains("lanes") && s["lanes"].is_string()) {
    const double lanes = std::atof(s["lanes"].get<std::string>().c_str());
    if (lanes >= 1 && lanes <= 20) return lanes * kLaneWidth + 2 * 1.5;  // plus the sidewalks
  }
  return class_width(s.contains("highway") ? s["highway"].get<std::string>() : "");
}

Vec2 local_of(const Json& position, const LocalFrameMapping& mapping) {
  const auto l = mapping.to_local(position[0].get<double>(), position[1].get<double>(), 0);
  return {l[0], l[1]};
}

}  // namespace

StreetNetwork osm_streets(const Json& streets, const std::string& file,
                          const LocalFrameMapping& mapping, ReadReport& report) {
  StreetNetwork net;
  for (const Json& s : streets) {
    const std::string id = s["id"].get<std::string>();
    if (s.contains("line")) {
      StreetLine line{id, {}, street_width(s, file, report)};
      for (const Json& p : s["line"]) line.points.push_back(local_of(p, mapping));
      net.lines.push_back(std::move(line));
    } else if (s.contains("area")) {
      std::vector<Ring> rings;
      for (const Json& ring : s["area"]) {
        Ring r;
        for (const Json& p : ring) r.push_back(local_of(p, mapping));
        rings.push_back(std::move(r));
      }
      // Repaired like footprints; an area beyond repair is left out (it only places cells).
      try {
        for (Polygon& p : clean_polygon(std::move(rings), {file, id, true, false}, report))
          net.areas.push_back(std::move(p));
      } catch (const InputError& e) {
        report.warnings.push_back(std::string(e.what()) + "; this street area is left out");
      }
    }
  }
  return net;
}

}  // namespace urbanpvs::geometry::detail
