// GeoJSON writer: one feature per line, coordinates in EPSG:31256 metres with three decimals.
#include "urbanpvs/cities/GeoJsonWriter.hpp"

#include <ostream>

#include "JsonText.hpp"

namespace urbanpvs::cities {
namespace {

using detail::appendInt;
using detail::appendMetres;
using detail::appendString;
using detail::toMillimetres;

const char* roofShape(RoofKind kind) {
  switch (kind) {
    case RoofKind::Gabled:
      return "gabled";
    case RoofKind::Hipped:
      return "hipped";
    case RoofKind::Flat:
      break;
  }
  return "flat";
}

class Writer {
 public:
  explicit Writer(const City& city)
      : city_(city),
        ox_(toMillimetres(city.params.origin_x)),
        oy_(toMillimetres(city.params.origin_y)) {}

  std::string run() {
    out_.reserve(256 + city_.buildings.size() * 600);
    out_ += "{\"type\":\"FeatureCollection\",\n";
    out_ +=
        "\"crs\":{\"type\":\"name\",\"properties\":{\"name\":\"urn:ogc:def:crs:EPSG::31256\"}},\n";
    out_ += "\"features\":[\n";
    for (const Building& b : city_.buildings) {
      const std::string& block_id = city_.blocks[b.block].id;
      if (b.parts.empty()) {
        feature(b.id, nullptr, block_id, b.footprint, b.eaves_height, b.ridge_height, b.roof,
                b.levels);
      }
      for (const BuildingPart& p : b.parts) {
        feature(p.id, &b.id, block_id, p.footprint, p.eaves_height, p.ridge_height, p.roof,
                p.levels);
      }
    }
    out_ += "\n]}\n";
    return std::move(out_);
  }

 private:
  void feature(const std::string& id, const std::string* parent, const std::string& block_id,
               const Polygon& fp, double eaves, double ridge, RoofKind roof, int levels) {
    if (!first_) out_ += ",\n";
    first_ = false;
    out_ += "{\"type\":\"Feature\",\"id\":";
    appendString(out_, id);
    out_ += ",\"properties\":{\"id\":";
    appendString(out_, id);
    out_ += ",\"block\":";
    appendString(out_, block_id);
    if (parent != nullptr) {
      out_ += ",\"building:part\":\"yes\",\"building\":";
      appendString(out_, *parent);
    }
    out_ += ",\"height\":";
    appendMetres(out_, toMillimetres(eaves));
    out_ += ",\"roof:height\":";
    appendMetres(out_, toMillimetres(ridge) - toMillimetres(eaves));
    out_ += ",\"roof:shape\":\"";
    out_ += roofShape(roof);
    out_ += "\",\"building:levels\":";
    appendInt(out_, levels);
    out_ += "},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[";
    ring(fp.outer);
    for (const Ring& hole : fp.holes) {
      out_ += ',';
      ring(hole);
    }
    out_ += "]}}";
  }

  // RFC 7946 rings repeat the first position; outer counter-clockwise, holes clockwise, which is
  // already the model's orientation.
  void ring(const Ring& r) {
    out_ += '[';
    for (std::size_t i = 0; i <= r.size(); ++i) {
      const Vec2& p = r[i % r.size()];
      if (i > 0) out_ += ',';
      out_ += '[';
      appendMetres(out_, ox_ + toMillimetres(p.x));
      out_ += ',';
      appendMetres(out_, oy_ + toMillimetres(p.y));
      out_ += ']';
    }
    out_ += ']';
  }

  const City& city_;
  std::int64_t ox_;
  std::int64_t oy_;
  std::string out_;
  bool first_ = true;
};

}  // namespace

std::string geoJsonText(const City& city) {
  return Writer(city).run();
}

void writeGeoJson(const City& city, std::ostream& out) {
  out << geoJsonText(city);
}

}  // namespace urbanpvs::cities
