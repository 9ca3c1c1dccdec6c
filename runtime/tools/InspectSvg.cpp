// SPDX-License-Identifier: MIT
// urbanpvs-inspect FILE --svg OUT.svg [--cell N]: a top-down map.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "Inspect.hpp"

namespace urbanpvs::inspect {
namespace {

constexpr double kWidthPx = 1000;
constexpr double kMarginPx = 10;

struct View {
  double min_x = 0, min_y = 0, max_x = 1, max_y = 1, scale = 1;
  double px(double x) const { return kMarginPx + (x - min_x) * scale; }
  double py(double y) const { return kMarginPx + (max_y - y) * scale; }  // SVG y points down
};

View make_view(const runtime::PvsFile& file) {
  View v;
  bool any = false;
  auto add = [&](double x, double y) {
    if (!any) {
      v.min_x = v.max_x = x;
      v.min_y = v.max_y = y;
      any = true;
    }
    v.min_x = std::min(v.min_x, x);
    v.max_x = std::max(v.max_x, x);
    v.min_y = std::min(v.min_y, y);
    v.max_y = std::max(v.max_y, y);
  };
  for (std::uint32_t i = 0; i < file.cell_count(); ++i) {
    runtime::CellGeometry c;
    file.cell(i, c);
    for (const auto& p : c.triangle) {
      const auto r = reported(file, p.x, p.y, 0);
      add(r[0], r[1]);
    }
  }
  for (std::uint32_t i = 0; i < file.object_count(); ++i) {
    runtime::ObjectInfo o;
    file.object(i, o);
    const auto lo = reported(file, o.bbox[0], o.bbox[1], 0);
    const auto hi = reported(file, o.bbox[3], o.bbox[4], 0);
    add(lo[0], lo[1]);
    add(hi[0], hi[1]);
  }
  const double extent = std::max({v.max_x - v.min_x, v.max_y - v.min_y, 1e-9});
  v.scale = (kWidthPx - 2 * kMarginPx) / extent;
  return v;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", v);
  return buf;
}

/// Light yellow (small PVS) to dark red (large PVS).
std::string ramp(double t) {
  t = std::clamp(t, 0.0, 1.0);
  const int r = static_cast<int>(255 + t * (189 - 255));
  const int g = static_cast<int>(247 + t * (0 - 247));
  const int b = static_cast<int>(188 + t * (38 - 188));
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", r, g, b);
  return buf;
}

std::string polygon(const runtime::PvsFile& file, const View& v, const runtime::CellGeometry& c) {
  std::string points;
  for (const auto& p : c.triangle) {
    const auto r = reported(file, p.x, p.y, 0);
    points += num(v.px(r[0])) + "," + num(v.py(r[1])) + " ";
  }
  points.pop_back();
  return "points=\"" + points + "\"";
}

std::string rect(const runtime::PvsFile& file, const View& v, const runtime::ObjectInfo& o) {
  const auto lo = reported(file, o.bbox[0], o.bbox[1], 0);
  const auto hi = reported(file, o.bbox[3], o.bbox[4], 0);
  return "x=\"" + num(v.px(lo[0])) + "\" y=\"" + num(v.py(hi[1])) + "\" width=\"" +
         num((hi[0] - lo[0]) * v.scale) + "\" height=\"" + num((hi[1] - lo[1]) * v.scale) + "\"";
}

}  // namespace

std::string render_svg(const runtime::PvsFile& file, std::optional<std::uint32_t> cell) {
  const View v = make_view(file);
  const double width = kWidthPx;
  const double height = 2 * kMarginPx + (v.max_y - v.min_y) * v.scale;
  std::uint32_t min_size = UINT32_MAX, max_size = 0;
  for (std::uint32_t i = 0; i < file.cell_count(); ++i) {
    min_size = std::min(min_size, file.pvs_size(i));
    max_size = std::max(max_size, file.pvs_size(i));
  }
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(width) + "\" height=\"" +
         num(height + 24) + "\" viewBox=\"0 0 " + num(width) + " " + num(height + 24) + "\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<g id=\"cells\" stroke=\"#999999\" stroke-width=\"0.2\">\n";
  for (std::uint32_t i = 0; i < file.cell_count(); ++i) {
    runtime::CellGeometry c;
    file.cell(i, c);
    const double t = max_size > min_size
                         ? double(file.pvs_size(i) - min_size) / double(max_size - min_size)
                         : 0.0;
    svg += "<polygon " + polygon(file, v, c) + " fill=\"" + ramp(t) + "\"/>\n";
  }
  svg += "</g>\n<g id=\"objects\">\n";
  runtime::PvsDecoder decoder(file);
  std::vector<char> visible(file.object_count(), 0);
  if (cell && decoder.decode(*cell) == runtime::Status::kOk) {
    for (std::uint32_t object : decoder) visible[object] = 1;
  }
  for (std::uint32_t i = 0; i < file.object_count(); ++i) {
    runtime::ObjectInfo o;
    file.object(i, o);
    const char* style =
        !cell ? "fill=\"none\" stroke=\"#555555\" stroke-width=\"0.5\""
        : visible[i]
            ? "fill=\"#2b8cbe\" fill-opacity=\"0.85\" stroke=\"#08519c\" stroke-width=\"0.6\""
            : "fill=\"#dddddd\" fill-opacity=\"0.6\" stroke=\"#aaaaaa\" stroke-width=\"0.4\"";
    svg += "<rect " + rect(file, v, o) + " " + style + "/>\n";
  }
  svg += "</g>\n";
  std::string caption =
      "cells shaded by PVS size: " + std::to_string(file.cell_count() ? min_size : 0) +
      " (light) to " + std::to_string(max_size) + " (dark)";
  if (cell) {
    runtime::CellGeometry c;
    file.cell(*cell, c);
    svg += "<polygon id=\"selected-cell\" " + polygon(file, v, c) +
           " fill=\"#31a354\" stroke=\"#000000\" stroke-width=\"1.5\"/>\n";
    caption += "; cell " + std::to_string(*cell) + " (green) sees " +
               std::to_string(decoder.size()) + " objects (blue), hidden in grey";
  }
  svg += "<text x=\"" + num(kMarginPx) + "\" y=\"" + num(height + 16) +
         "\" font-family=\"sans-serif\" font-size=\"12\">" + caption + "</text>\n</svg>\n";
  return svg;
}

}  // namespace urbanpvs::inspect
