// CityJSON 2.0 writer. The text is laid out one CityObject and one vertex per line so that the
// bundled sample diffs readably in git; vertices are integers in millimetres relative to the
// transform's translate (the city origin).
#include "urbanpvs/cities/CityJsonWriter.hpp"

#include <algorithm>
#include <array>
#include <ostream>
#include <vector>

#include "JsonText.hpp"

namespace urbanpvs::cities {
namespace {

using detail::appendInt;
using detail::appendMetres;
using detail::appendString;
using detail::toMillimetres;

// The roof type names of CityGML's code list (CityJSON schemas up to 1.0 enumerate them).
const char* roofTypeName(RoofKind kind) {
  switch (kind) {
    case RoofKind::Gabled:
      return "gabled roof";
    case RoofKind::Hipped:
      return "hipped roof";
    case RoofKind::Flat:
      break;
  }
  return "flat roof";
}

int semanticIndex(SurfaceType type) {
  switch (type) {
    case SurfaceType::Ground:
      return 0;
    case SurfaceType::Wall:
      return 1;
    case SurfaceType::Roof:
      return 2;
  }
  return 1;
}

class Writer {
 public:
  explicit Writer(const City& city) : city_(city) {}

  std::string run() {
    // The header's geographical extent needs every vertex, so the objects are written first.
    out_.reserve(city_.buildings.size() * 1200);
    writeObjects();
    std::string objects = std::move(out_);
    out_.clear();
    out_.reserve(objects.size() + vertices_.size() * 24 + 1024);
    writeHeader();
    out_ += "\"CityObjects\":{\n";
    out_ += objects;
    out_ += "},\n\"vertices\":[\n";
    for (std::size_t i = 0; i < vertices_.size(); ++i) {
      const auto& v = vertices_[i];
      out_ += '[';
      appendInt(out_, v[0]);
      out_ += ',';
      appendInt(out_, v[1]);
      out_ += ',';
      appendInt(out_, v[2]);
      out_ += i + 1 < vertices_.size() ? "],\n" : "]\n";
    }
    out_ += "]\n}\n";
    return std::move(out_);
  }

 private:
  void writeHeader() {
    const std::int64_t ox = toMillimetres(city_.params.origin_x);
    const std::int64_t oy = toMillimetres(city_.params.origin_y);
    out_ += "{\"type\":\"CityJSON\",\"version\":\"2.0\",\n";
    out_ += "\"transform\":{\"scale\":[0.001,0.001,0.001],\"translate\":[";
    appendMetres(out_, ox);
    out_ += ',';
    appendMetres(out_, oy);
    out_ += ",0.000]},\n";
    out_ += "\"metadata\":{\"referenceSystem\":\"https://www.opengis.net/def/crs/EPSG/0/31256\",";
    out_ += "\"geographicalExtent\":[";
    std::array<std::int64_t, 6> ext{0, 0, 0, toMillimetres(city_.side), toMillimetres(city_.side),
                                    0};
    if (!vertices_.empty()) {
      ext = {vertices_[0][0], vertices_[0][1], vertices_[0][2],
             vertices_[0][0], vertices_[0][1], vertices_[0][2]};
      for (const auto& v : vertices_) {
        for (int k = 0; k < 3; ++k) {
          ext[k] = std::min(ext[k], v[k]);
          ext[k + 3] = std::max(ext[k + 3], v[k]);
        }
      }
    }
    const std::array<std::int64_t, 6> offset{ox, oy, 0, ox, oy, 0};
    for (int k = 0; k < 6; ++k) {
      if (k > 0) out_ += ',';
      appendMetres(out_, ext[k] + offset[k]);
    }
    out_ += "],\"title\":\"urbanpvs procedural city, side ";
    appendMetres(out_, toMillimetres(city_.side));
    out_ += " m, seed ";
    out_ += std::to_string(city_.params.seed);
    out_ += ", roofs ";
    out_ += toString(city_.params.roofs);
    if (city_.params.hills > 0) {
      out_ += ", hills ";
      appendMetres(out_, toMillimetres(city_.params.hills));
      out_ += " m";
    }
    out_ += "\"},\n";
  }

  // The relief as one TINRelief: every grid square two triangles, counter-clockwise from above.
  void writeTerrain(bool first) {
    const Terrain& t = city_.terrain;
    const auto base = static_cast<std::uint32_t>(vertices_.size());
    for (int j = 0; j < t.rows; ++j)
      for (int i = 0; i < t.columns; ++i)
        vertices_.push_back({toMillimetres(t.origin.x + i * t.spacing),
                             toMillimetres(t.origin.y + j * t.spacing), toMillimetres(t.at(i, j))});
    if (!first) out_ += ",\n";
    out_ += "\"terrain\":{\"type\":\"TINRelief\",\"geometry\":[{\"type\":\"CompositeSurface\",";
    out_ += "\"lod\":\"1\",\"boundaries\":[";
    auto node = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * t.columns + i); };
    auto triangle = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, bool comma) {
      if (comma) out_ += ',';
      out_ += "[[";
      appendInt(out_, a);
      out_ += ',';
      appendInt(out_, b);
      out_ += ',';
      appendInt(out_, c);
      out_ += "]]";
    };
    bool comma = false;
    for (int j = 0; j + 1 < t.rows; ++j)
      for (int i = 0; i + 1 < t.columns; ++i) {
        triangle(node(i, j), node(i + 1, j), node(i + 1, j + 1), comma);
        triangle(node(i, j), node(i + 1, j + 1), node(i, j + 1), true);
        comma = true;
      }
    out_ += "]}]}\n";
  }

  void writeObjects() {
    bool first = true;
    for (const Building& b : city_.buildings) {
      const std::string& block_id = city_.blocks[b.block].id;
      auto separator = [&] {
        if (!first) out_ += ",\n";
        first = false;
      };
      separator();
      appendString(out_, b.id);
      out_ += ":{\"type\":\"Building\",";
      writeAttributes(b.eaves_height, b.ridge_height, b.roof, b.levels, block_id);
      if (b.parts.empty()) {
        out_ += ',';
        writeGeometry(b.solid);
      } else {
        // No geometry of its own (some schema versions require the member): the parts have it.
        out_ += ",\"geometry\":[],\"children\":[";
        for (std::size_t k = 0; k < b.parts.size(); ++k) {
          if (k > 0) out_ += ',';
          appendString(out_, b.parts[k].id);
        }
        out_ += ']';
      }
      out_ += '}';
      for (const BuildingPart& part : b.parts) {
        separator();
        appendString(out_, part.id);
        out_ += ":{\"type\":\"BuildingPart\",\"parents\":[";
        appendString(out_, b.id);
        out_ += "],";
        writeAttributes(part.eaves_height, part.ridge_height, part.roof, part.levels, block_id);
        out_ += ',';
        writeGeometry(part.solid);
        out_ += '}';
      }
    }
    if (!city_.terrain.empty()) {
      out_ += '\n';
      writeTerrain(first);
      return;
    }
    out_ += '\n';
  }

  void writeAttributes(double eaves, double ridge, RoofKind roof, int levels,
                       const std::string& block_id) {
    out_ += "\"attributes\":{\"measuredHeight\":";
    appendMetres(out_, toMillimetres(ridge));
    out_ += ",\"eavesHeight\":";
    appendMetres(out_, toMillimetres(eaves));
    out_ += ",\"roofType\":\"";
    out_ += roofTypeName(roof);
    out_ += "\",\"storeysAboveGround\":";
    appendInt(out_, levels);
    out_ += ",\"block\":";
    appendString(out_, block_id);
    out_ += '}';
  }

  void writeGeometry(const Solid& solid) {
    const auto base = static_cast<std::uint32_t>(vertices_.size());
    for (const Vec3& v : solid.vertices) {
      vertices_.push_back({toMillimetres(v.x), toMillimetres(v.y), toMillimetres(v.z)});
    }
    out_ += "\"geometry\":[{\"type\":\"Solid\",\"lod\":\"";
    out_ += city_.params.roofs == RoofMode::Lod2 ? "2.2" : "1.2";
    out_ += "\",\"boundaries\":[[";
    for (std::size_t f = 0; f < solid.faces.size(); ++f) {
      if (f > 0) out_ += ',';
      out_ += '[';
      const auto& rings = solid.faces[f].rings;
      for (std::size_t r = 0; r < rings.size(); ++r) {
        if (r > 0) out_ += ',';
        out_ += '[';
        for (std::size_t i = 0; i < rings[r].size(); ++i) {
          if (i > 0) out_ += ',';
          appendInt(out_, base + rings[r][i]);
        }
        out_ += ']';
      }
      out_ += ']';
    }
    out_ +=
        "]],\"semantics\":{\"surfaces\":[{\"type\":\"GroundSurface\"},{\"type\":\"WallSurface\"},";
    out_ += "{\"type\":\"RoofSurface\"}],\"values\":[[";
    for (std::size_t f = 0; f < solid.faces.size(); ++f) {
      if (f > 0) out_ += ',';
      appendInt(out_, semanticIndex(solid.faces[f].type));
    }
    out_ += "]]}}]";
  }

  const City& city_;
  std::string out_;
  std::vector<std::array<std::int64_t, 3>> vertices_;
};

}  // namespace

std::string cityJsonText(const City& city) {
  return Writer(city).run();
}

void writeCityJson(const City& city, std::ostream& out) {
  out << cityJsonText(city);
}

}  // namespace urbanpvs::cities
