// SPDX-License-Identifier: GPL-3.0-or-later
// A top-down SVG map in local coordinates, for people to look at footprints, blocks, occluders
// and view cells. North is up (SVG's y axis points down, so y is flipped).
#pragma once

#include <array>
#include <sstream>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::geometry {

class SvgMap {
 public:
  /// `view` is the area shown; `width_px` the picture's width.
  SvgMap(const Box2& view, double width_px = 1600);

  void polygon(const Polygon& p, const std::string& style);
  void triangle(Vec2 a, Vec2 b, Vec2 c, const std::string& style);
  /// Many triangles as one path of one style: a mesh of 20,000 view cells stays a small file.
  void triangles(const std::vector<std::array<Vec2, 3>>& ts, const std::string& style);
  void text(Vec2 at, const std::string& s, const std::string& style);

  /// The finished document.
  std::string str() const;

 private:
  std::string point(Vec2 p) const;
  Box2 view_;
  double scale_;
  std::ostringstream body_;
};

}  // namespace urbanpvs::geometry
