// SPDX-License-Identifier: GPL-3.0-or-later
// Building footprints from the vector formats of GIS (Shapefile, GeoPackage, FlatGeobuf, MapInfo
// TAB, SpatiaLite), read with GDAL/OGR. Footprint datasets are published in these formats far
// more often than as GeoJSON (national cadastres, municipal open data, Esri exports); OGR reads
// all of them through one interface. Each feature is handed on as a GeoJSON feature with its
// fields as properties, the way the OpenStreetMap reader does it, so heights (height,
// building:levels, --height-field), parts, ring repair and the local frame follow exactly the
// GeoJSON reader's rules.
//
// Coordinates stay as they are when the layer's system is projected, in metres and known by an
// EPSG code: the local frame then keeps that code. Any other system PROJ knows (a state plane in
// feet, a national grid without a code, a geographic system other than WGS84) is transformed to
// WGS84 longitude/latitude, which the GeoJSON reader projects to its local east-north-up frame;
// the summary says so. GeoJSON, which can only name a code, must be reprojected by the user.
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "CityReaders.hpp"
#include "GdalHandles.hpp"
#include "InputReprojection.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

bool is_polygonal(OGRwkbGeometryType t) {
  switch (wkbFlatten(t)) {
    case wkbPolygon:
    case wkbMultiPolygon:
    case wkbCurvePolygon:
    case wkbMultiSurface:
    case wkbGeometryCollection:
    case wkbUnknown:  // mixed layers (GeoJSON-like sources): the features decide
      return true;
    default:
      return false;
  }
}

// A polygon standing on edge in plan (a wall of an Esri multipatch or a PolyhedralSurface): it
// has no area to stand on, and the GeoJSON rules would take it for a broken footprint.
bool vertical(const OGRLinearRing& ring) {
  double perimeter = 0;
  for (int i = 1; i < ring.getNumPoints(); ++i)
    perimeter += std::hypot(ring.getX(i) - ring.getX(i - 1), ring.getY(i) - ring.getY(i - 1));
  return !(std::abs(ring.get_Area()) > 1e-9 * perimeter * perimeter);
}

Json ring_json(const OGRLinearRing& ring) {
  Json out = Json::array();
  for (int i = 0; i < ring.getNumPoints(); ++i)
    out.push_back(Json::array({ring.getX(i), ring.getY(i)}));
  return out;
}

// The polygons of `g` as GeoJSON MultiPolygon coordinates; collections are searched, curves were
// linearised before. Empty and vertical polygons are counted in `vertical_count`, not added.
void add_polygons(const OGRGeometry& g, Json& polygons, std::size_t& vertical_count) {
  const OGRwkbGeometryType t = wkbFlatten(g.getGeometryType());
  if (t == wkbPolygon) {
    const auto& p = *g.toPolygon();
    const OGRLinearRing* outer = p.getExteriorRing();
    if (outer == nullptr || outer->IsEmpty()) return;
    if (vertical(*outer)) {
      ++vertical_count;
      return;
    }
    Json rings = Json::array({ring_json(*outer)});
    for (int k = 0; k < p.getNumInteriorRings(); ++k)
      if (!p.getInteriorRing(k)->IsEmpty()) rings.push_back(ring_json(*p.getInteriorRing(k)));
    polygons.push_back(std::move(rings));
  } else if (t == wkbMultiPolygon || t == wkbGeometryCollection) {
    for (const OGRGeometry* part : *g.toGeometryCollection())
      add_polygons(*part, polygons, vertical_count);
  }
}

// A field as the JSON value a GeoJSON writer would give it; null when unset or null.
Json field_json(const OGRFeature& f, int i) {
  if (!f.IsFieldSetAndNotNull(i)) return nullptr;
  switch (f.GetFieldDefnRef(i)->GetType()) {
    case OFTInteger:
      return f.GetFieldAsInteger(i);
    case OFTInteger64:
      return static_cast<long long>(f.GetFieldAsInteger64(i));
    case OFTReal:
      return f.GetFieldAsDouble(i);
    default:
      return f.GetFieldAsString(i);
  }
}

std::string names_of(const std::vector<OGRLayer*>& layers) {
  std::string names;
  for (OGRLayer* l : layers) names += (names.empty() ? "" : ", ") + std::string(l->GetName());
  return names.empty() ? "none" : names;
}

std::string layer_list(GDALDataset& ds) {
  std::vector<OGRLayer*> all;
  for (OGRLayer* l : ds.GetLayers()) all.push_back(l);
  return names_of(all);
}

// The layer to read: the one named, the only one, or the only one of polygons.
OGRLayer& chosen_layer(GDALDataset& ds, const std::string& path, const std::string& wanted) {
  if (!wanted.empty()) {
    if (OGRLayer* l = ds.GetLayerByName(wanted.c_str())) return *l;
    throw InputError(InputProblem::BadStructure, path, "",
                     "no layer \"" + wanted + "\" (layers: " + layer_list(ds) + ")");
  }
  std::vector<OGRLayer*> polygonal;
  for (OGRLayer* l : ds.GetLayers())
    if (is_polygonal(l->GetGeomType())) polygonal.push_back(l);
  if (polygonal.size() == 1) return *polygonal.front();
  if (polygonal.empty())
    throw InputError(InputProblem::EmptyCity, path, "",
                     "no layer of polygons (layers: " + layer_list(ds) + ")");
  throw InputError(InputProblem::BadStructure, path, "",
                   std::to_string(polygonal.size()) + " layers of polygons (" +
                       names_of(polygonal) + "): name the one to read with --layer");
}

// Where the layer's coordinates must go: nothing to do (projected metres with an EPSG code,
// named in `crs`), or a transformation to WGS84 lon/lat (`to_wgs84`), described in `note`.
struct LayerSystem {
  Json crs;  ///< the GeoJSON "crs" member; null: none (the reader decides from the range)
  std::unique_ptr<OGRCoordinateTransformation, TransformDeleter> to_wgs84;
  std::string note;
};

LayerSystem layer_system(OGRLayer& layer, const std::string& path) {
  LayerSystem out;
  const OGRSpatialReference* given = layer.GetSpatialRef();
  if (given == nullptr) return out;
  OGRSpatialReference s(*given);
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = east / longitude
  auto name = [](const char* text) {
    return Json{{"type", "name"}, {"properties", {{"name", text}}}};
  };
  // A system given only as WKT (a GeoPackage's own definition, a MapInfo file) keeps its EPSG
  // code where PROJ's catalogue matches it with confidence.
  if (is_metric_projection(s))
    if (const std::string code = authority_code(s); code.rfind("EPSG:", 0) == 0) {
      out.crs = name(code.c_str());
      return out;
    }
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  out.crs = name("urn:ogc:def:crs:OGC:1.3:CRS84");
  if (s.IsGeographic() && s.IsSame(&wgs84)) return out;
  Reprojection r = reprojection_from(s, crs_name(s), path, layer.GetName());
  out.to_wgs84 = std::move(r.to_wgs84);
  out.note = path + ": " + r.from + " transformed to WGS84 lon/lat";
  return out;
}

}  // namespace

bool is_gis_vector_file(const std::string& path) {
  for (const char* ext : {".shp", ".shz", ".shp.zip", ".gpkg", ".fgb", ".tab", ".sqlite"})
    if (has_extension(path, ext)) return true;
  return false;
}

Json read_gis_vector(const std::string& path, const ReadOptions& options, ReadReport& report) {
  open_input_file(path);  // the project's own messages for a missing or unreadable file
  const QuietGdal quiet;
  // A zipped shapefile is read where it lies, without unpacking it.
  const std::string where = has_extension(path, ".shp.zip") ? "/vsizip/" + path : path;
  std::unique_ptr<GDALDataset, DatasetCloser> ds(GDALDataset::FromHandle(
      GDALOpenEx(where.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!ds)
    throw InputError(InputProblem::UnsupportedFormat, path, "",
                     "no vector data GDAL can read (Shapefile, GeoPackage, FlatGeobuf, ...)" +
                         QuietGdal::last());
  OGRLayer& layer = chosen_layer(*ds, path, options.layer);
  LayerSystem system = layer_system(layer, path);
  if (!system.note.empty()) report.warnings.push_back(system.note);

  OGRFeatureDefn& defn = *layer.GetLayerDefn();
  Json features = Json::array();
  std::size_t without = 0, untransformed = 0, walls = 0, index = 0;
  std::string first_without, first_untransformed;
  layer.ResetReading();
  CPLErrorReset();
  for (auto& f : layer) {
    // Formats without feature ids give none (OGRNullFID): the position in the layer then.
    const std::string fid =
        std::to_string(f->GetFID() != OGRNullFID ? f->GetFID() : GIntBig(index));
    ++index;
    OGRGeometryUniquePtr geometry(f->StealGeometry());
    if (geometry && geometry->hasCurveGeometry())
      geometry.reset(geometry->getLinearGeometry());  // arcs as segments
    if (geometry && system.to_wgs84 && geometry->transform(system.to_wgs84.get()) != OGRERR_NONE) {
      if (untransformed++ == 0) first_untransformed = fid;
      CPLErrorReset();  // PROJ's error for this feature is no read error of the layer
      continue;
    }
    Json polygons = Json::array();
    if (geometry) add_polygons(*geometry, polygons, walls);
    if (polygons.empty()) {
      if (without++ == 0) first_without = fid;
      continue;
    }
    Json properties = Json::object();
    // An unset or null field is left out: most formats cannot tell it from absent, and the
    // GeoJSON rules read a member that is there (building:part, min_height) as given.
    for (int i = 0; i < defn.GetFieldCount(); ++i)
      if (Json v = field_json(*f, i); !v.is_null())
        properties[defn.GetFieldDefn(i)->GetNameRef()] = std::move(v);
    Json feature = {{"type", "Feature"},
                    {"properties", std::move(properties)},
                    {"geometry", {{"type", "MultiPolygon"}, {"coordinates", std::move(polygons)}}}};
    // Ids: a feature's own "id" (or an OSM export's "@id") field, as the GeoJSON reader takes
    // them (a GeoJSON turned into a GeoPackage keeps string ids there), else its FID, the key
    // GIS tools show. Matched exactly: ArcGIS's "Id" field of zeros is no id.
    const Json& p = feature["properties"];
    auto named = [&](const char* key) {
      const auto it = p.find(key);
      return it != p.end() && !(it->is_string() && it->get_ref<const std::string&>().empty());
    };
    if (!named("id") && !named("@id")) feature["id"] = fid;
    features.push_back(std::move(feature));
  }
  // A damaged record ends the loop as the end of the layer would: say so, rather than bake a
  // part of the city.
  if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
    throw InputError(
        InputProblem::Unreadable, path, layer.GetName(),
        "reading stopped after " + std::to_string(index) + " features" + QuietGdal::last());
  const std::string in = path + ": layer " + layer.GetName() + ": ";
  if (without)
    report.warnings.push_back(in + std::to_string(without) +
                              " feature(s) without polygons (points, lines, no geometry; first "
                              "FID " +
                              first_without + ") left out");
  if (walls)
    report.warnings.push_back(in + std::to_string(walls) +
                              " vertical polygon(s) (walls of 3D surfaces such as Esri "
                              "multipatches) left out; the rest of such a feature is read as "
                              "its footprint");
  if (untransformed)
    report.warnings.push_back(in + std::to_string(untransformed) +
                              " feature(s) PROJ could not transform to WGS84 (first FID " +
                              first_untransformed + ") left out");
  Json doc = {{"type", "FeatureCollection"}, {"features", std::move(features)}};
  if (!system.crs.is_null()) doc["crs"] = std::move(system.crs);
  return doc;
}

}  // namespace urbanpvs::geometry::detail
