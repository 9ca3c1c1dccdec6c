// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/cells/SvgMap.hpp"

#include <cstdio>
#include <stdexcept>

namespace urbanpvs::geometry {

SvgMap::SvgMap(const Box2& view, double width_px) : view_(view) {
  const double w = std::max(view.max.x - view.min.x, 1e-9);
  scale_ = width_px / w;
}

std::string SvgMap::point(Vec2 p) const {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f,%.1f", (p.x - view_.min.x) * scale_,
                (view_.max.y - p.y) * scale_);
  return buf;
}

void SvgMap::polygon(const Polygon& p, const std::string& style) {
  body_ << "<path fill-rule=\"evenodd\" style=\"" << style << "\" d=\"";
  auto ring = [&](const Ring& r) {
    for (std::size_t i = 0; i < r.size(); ++i) body_ << (i ? "L" : "M") << point(r[i]);
    body_ << "Z";
  };
  ring(p.outer);
  for (const Ring& h : p.holes) ring(h);
  body_ << "\"/>\n";
}

void SvgMap::triangle(Vec2 a, Vec2 b, Vec2 c, const std::string& style) {
  body_ << "<path style=\"" << style << "\" d=\"M" << point(a) << "L" << point(b) << "L" << point(c)
        << "Z\"/>\n";
}

void SvgMap::triangles(const std::vector<std::array<Vec2, 3>>& ts, const std::string& style) {
  if (ts.empty()) return;
  body_ << "<path style=\"" << style << "\" d=\"";
  for (const auto& t : ts)
    body_ << "M" << point(t[0]) << "L" << point(t[1]) << "L" << point(t[2]) << "Z";
  body_ << "\"/>\n";
}

void SvgMap::text(Vec2 at, const std::string& s, const std::string& style) {
  const std::string xy = point(at);
  const auto comma = xy.find(',');
  body_ << "<text x=\"" << xy.substr(0, comma) << "\" y=\"" << xy.substr(comma + 1) << "\" style=\""
        << style << "\">" << s << "</text>\n";
}

std::string SvgMap::str() const {
  char head[256];
  std::snprintf(head, sizeof head,
                "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\">\n"
                "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n",
                (view_.max.x - view_.min.x) * scale_, (view_.max.y - view_.min.y) * scale_);
  return head + body_.str() + "</svg>\n";
}

}  // namespace urbanpvs::geometry
