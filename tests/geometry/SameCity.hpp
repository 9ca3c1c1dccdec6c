// SPDX-License-Identifier: GPL-3.0-or-later
// One city read from two encodings of the same data (a CityJSON file and its text sequence, or
// its CityGML) must give the same objects: every coordinate to the last bit.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <string>

#include "urbanpvs/geometry/city/CityReader.hpp"

namespace urbanpvs::test {

// What the reader made of an object, every coordinate to the last bit.
inline std::string digest(const geometry::CityObject& o) {
  std::string s;
  char b[64];
  const auto number = [&](double v) {
    std::snprintf(b, sizeof b, "%.17g ", v);
    s += b;
  };
  const auto polygon = [&](const geometry::Polygon& p) {
    for (const geometry::Vec2& v : p.outer) number(v.x), number(v.y);
    for (const geometry::Ring& h : p.holes) {
      s += "| ";
      for (const geometry::Vec2& v : h) number(v.x), number(v.y);
    }
    s += "; ";
  };
  s += o.occludes ? "occludes " : "occludes nothing ";
  for (double v : {o.bbox.xy.min.x, o.bbox.xy.min.y, o.bbox.zmin, o.bbox.xy.max.x, o.bbox.xy.max.y,
                   o.bbox.zmax, o.ground_z})
    number(v);
  for (const geometry::Polygon& p : o.footprint) polygon(p);
  for (const geometry::OccluderPrism& prism : o.occluders) {
    polygon(prism.footprint);
    number(prism.ground_z), number(prism.top_z);
  }
  s += std::to_string(o.surfaces.size()) + " surfaces";
  return s;
}

inline void expect_same_city(const geometry::City& file, const geometry::City& sequence) {
  ASSERT_EQ(file.objects.size(), sequence.objects.size());
  std::map<std::string, std::string> by_id;
  for (const geometry::CityObject& o : file.objects) by_id[o.source_id] = digest(o);
  for (const geometry::CityObject& o : sequence.objects) {
    ASSERT_TRUE(by_id.count(o.source_id)) << o.source_id;
    EXPECT_EQ(by_id[o.source_id], digest(o)) << o.source_id;
  }
  EXPECT_EQ(file.frame.crs, sequence.frame.crs);
  EXPECT_EQ(file.report.repaired_orientation, sequence.report.repaired_orientation);
  EXPECT_EQ(file.report.repaired_duplicate_points, sequence.report.repaired_duplicate_points);
}

}  // namespace urbanpvs::test
