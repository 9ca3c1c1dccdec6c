// SPDX-License-Identifier: GPL-3.0-or-later
// CityGML (1.0, 2.0 and 3.0): the format most LoD1/LoD2 city models are published in (the
// German states' LoD2 data, Vienna, New York, Japan's PLATEAU). Its buildings and building parts
// are turned into the CityJSON document the CityJSON reader knows, the way CityJSON's own
// converters map one onto the other, so both formats go through one reader with one set of
// repairs and rules:
//  - a bldg:Building or bldg:BuildingPart becomes a Building or BuildingPart with its
//    parents/children, keyed by its gml:id;
//  - each geometry property (lod0FootPrint, lod1Solid, lod2MultiSurface, the lod2MultiSurface of a
//    boundedBy RoofSurface / WallSurface / GroundSurface / ...) adds its polygons to one
//    MultiSurface per LoD, with the thematic surface as its semantics;
//  - surface members given by xlink:href (a lod2Solid made of the boundedBy polygons, as most
//    LoD2 data is written, or of a surface or solid given elsewhere) are resolved by gml:id to
//    the polygons of what they name, and a polygon met twice in one LoD is taken once;
//  - installations, rooms, furniture and openings are no volume a prism from the ground may
//    fill (thesis 7.1): their polygons are not the building's;
//  - generic attributes become attributes (what --payload reads);
//  - a dem:TINRelief's triangles become a TINRelief, the terrain; other city objects (vegetation,
//    bridges, roads) are listed as ignored types, as the CityJSON reader lists them.
// The file is read with expat, a streaming parser: CityGML tiles run to hundreds of megabytes.
#include <expat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <map>
#include <memory>
#include <new>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "CityReaders.hpp"
#include "InputReprojection.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

using Point = std::array<double, 3>;
using Ring = std::vector<Point>;

struct GmlPolygon {
  std::vector<Ring> rings;  // exterior first
  std::string semantic;     // the thematic surface it was written under, if any
  bool unreadable = false;  // a ring's coordinates could not be read: the polygon is left out
};

// One polygon of an object's geometry at one LoD: by index, or by a gml:id to resolve.
struct Member {
  int lod = 0;
  std::string semantic;
  std::optional<std::size_t> polygon;
  std::string href;
};

struct GmlObject {
  std::string id;
  std::string type;  // "Building" or "BuildingPart"
  std::optional<std::size_t> parent;
  std::vector<Member> members;
  std::optional<double> measured_height;
  std::vector<std::pair<std::string, std::string>> attributes;  // generic attributes, in order
  /// Why a polygon of it could not be read (the first such reason), or empty. Its other
  /// polygons cannot be trusted to bound an occluder (a roof face missing lifts the top), so
  /// the CityJSON reader keeps it as an object that occludes nothing (kUnreadableMember).
  std::string unreadable;
};

// Names without their namespace prefix: "bldg:RoofSurface" -> "RoofSurface".
std::string_view local_name(const char* name) {
  std::string_view n(name);
  const auto colon = n.rfind(':');
  return colon == std::string_view::npos ? n : n.substr(colon + 1);
}

const char* attribute(const char** attributes, std::string_view wanted) {
  for (const char** a = attributes; *a != nullptr; a += 2)
    if (local_name(a[0]) == wanted) return a[1];
  return nullptr;
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

bool is_thematic_surface(std::string_view n) {
  return n == "RoofSurface" || n == "WallSurface" || n == "GroundSurface" ||
         n == "ClosureSurface" || n == "OuterCeilingSurface" || n == "OuterFloorSurface" ||
         n == "FloorSurface" || n == "CeilingSurface" || n == "InteriorWallSurface";
}

// Parts of a building that are no part of its volume standing on the ground.
bool is_excluded_feature(std::string_view n) {
  return n.find("Installation") != std::string_view::npos ||
         n.find("Furniture") != std::string_view::npos || n == "Room" || n == "Window" ||
         n == "Door" || n == "Opening" || n == "BuildingRoom" || n == "BuildingConstructiveElement";
}

// "lod2MultiSurface" -> 2; "lod0FootPrint" -> 0; anything else -> nullopt.
std::optional<int> lod_property(std::string_view n) {
  if (n.size() < 5 || n.substr(0, 3) != "lod" || !std::isdigit(static_cast<unsigned char>(n[3])))
    return std::nullopt;
  return n[3] - '0';
}

// Reference systems as CityGML files name them: the German surveying offices' own names
// ("urn:adv:crs:ETRS89_UTM32*DE_DHHN2016_NH") name the UTM zone on ETRS89 or, in older data
// (Bavaria's LoD2 among them), the Gauss-Krüger zone on DHDN; everything else, compound URNs
// included, is normalise_crs's.
std::string horizontal_crs(const std::string& name) {
  static constexpr std::pair<const char*, const char*> kAdvNames[] = {
      {"ETRS89_UTM31", "EPSG:25831"}, {"ETRS89_UTM32", "EPSG:25832"},
      {"ETRS89_UTM33", "EPSG:25833"}, {"DE_DHDN_3GK2", "EPSG:31466"},
      {"DE_DHDN_3GK3", "EPSG:31467"}, {"DE_DHDN_3GK4", "EPSG:31468"},
      {"DE_DHDN_3GK5", "EPSG:31469"}};
  for (const auto& [adv, epsg] : kAdvNames)
    if (name.find(adv) != std::string::npos) return epsg;
  // "#local-CRS-1": a reference system the file defines itself (CityGML 3.0's EngineeringCRS,
  // a local Cartesian frame in metres), read as a file that names none is: local metres.
  if (!name.empty() && name.front() == '#') return {};
  return name;  // compound URNs: normalise_crs takes their horizontal part
}

class CityGmlParser {
 public:
  explicit CityGmlParser(const std::string& file) : file_(file) {}

  Json parse(std::string_view text) {
    const std::unique_ptr<XML_ParserStruct, decltype(&XML_ParserFree)> owner(
        XML_ParserCreate(nullptr), &XML_ParserFree);
    XML_Parser p = owner.get();
    if (p == nullptr) throw std::bad_alloc();
    parser_ = p;
    XML_SetUserData(p, this);
    XML_SetElementHandler(p, &CityGmlParser::on_start, &CityGmlParser::on_end);
    XML_SetCharacterDataHandler(p, &CityGmlParser::on_text);
    bool ok = true;
    // XML_Parse takes an int length: feed the text in pieces.
    constexpr std::size_t kPiece = std::size_t{1} << 30;
    for (std::size_t at = 0; ok && (at < text.size() || at == 0); at += kPiece) {
      const std::size_t n = std::min(kPiece, text.size() - at);
      const bool last = at + n >= text.size();
      ok = XML_Parse(p, text.data() + at, static_cast<int>(n), last ? 1 : 0) != XML_STATUS_ERROR;
      if (last) break;
    }
    const std::string where = "line " + std::to_string(XML_GetCurrentLineNumber(p)) + ", column " +
                              std::to_string(XML_GetCurrentColumnNumber(p));
    const char* expat_error = ok ? "" : XML_ErrorString(XML_GetErrorCode(p));  // NULL when none
    const std::string problem = expat_error != nullptr ? expat_error : "malformed XML";
    if (pending_) std::rethrow_exception(pending_);
    if (error_) throw *error_;
    if (!ok) throw InputError(InputProblem::InvalidXml, file_, where, problem);
    return document();
  }

 private:
  struct Context {  // what a geometry property holds
    int lod = 0;
    std::string semantic;
  };

  // No exception may unwind through expat's C frames (out of memory, say): it is kept, the
  // parse stopped, and it is thrown again once expat has returned.
  template <class F>
  static void guarded(void* self, F&& f) {
    auto* me = static_cast<CityGmlParser*>(self);
    try {
      f(*me);
    } catch (...) {
      if (!me->pending_) me->pending_ = std::current_exception();
      XML_StopParser(me->parser_, XML_FALSE);
    }
  }
  static void on_start(void* self, const char* name, const char** attributes) {
    guarded(self, [&](CityGmlParser& me) { me.start(local_name(name), attributes); });
  }
  static void on_end(void* self, const char* name) {
    guarded(self, [&](CityGmlParser& me) { me.end(local_name(name)); });
  }
  static void on_text(void* self, const char* s, int n) {
    guarded(self, [&](CityGmlParser& me) {
      if (me.collecting_) me.text_.append(s, static_cast<std::size_t>(n));
    });
  }

  // Stops the parse with an InputError thrown once expat has returned (an exception must not
  // unwind through its C frames).
  void fail(InputProblem problem, const std::string& feature, const std::string& what) {
    if (!error_) error_ = InputError(problem, file_, feature, what);
    XML_StopParser(parser_, XML_FALSE);
  }

  std::string current_id() const {
    return objects_.empty() || object_stack_.empty() ? std::string("(no building)")
                                                     : objects_[object_stack_.back()].id;
  }

  void start(std::string_view n, const char** attributes) {
    names_.emplace_back(n);
    if (const char* srs = attribute(attributes, "srsName"); srs != nullptr && crs_.empty())
      crs_ = horizontal_crs(srs);
    if (const char* d = attribute(attributes, "srsDimension"))
      dimension_stack_.push_back(std::atoi(d));
    else
      dimension_stack_.push_back(dimension_stack_.empty() ? 3 : dimension_stack_.back());
    if (names_.size() == 1 && n != "CityModel" && n != "FeatureCollection" && n != "Building") {
      // XML, but no CityGML: said as such, not as a city without buildings. (The stacks stay
      // balanced: expat may still report this element's end.)
      fail(InputProblem::UnsupportedFormat, "",
           n == "osm"
               ? "OpenStreetMap XML: name the file .osm (or .osm.gz, .osm.bz2)"
               : "XML whose root element is <" + std::string(n) + ">, not a CityGML CityModel");
      excluded_depth_ = 1;
      return;
    }
    if (excluded_depth_ > 0) {
      ++excluded_depth_;
      return;
    }
    if (is_excluded_feature(n)) {
      excluded_depth_ = 1;
      return;
    }
    if (names_.size() >= 2 &&
        (names_[names_.size() - 2] == "cityObjectMember" ||
         names_[names_.size() - 2] == "featureMember") &&
        n != "Building" && n != "ReliefFeature") {
      // Another kind of city object (vegetation, a bridge, a road): listed as ignored.
      const char* id = attribute(attributes, "id");
      ignored_.push_back(
          {id != nullptr ? id : std::string(n) + "-" + std::to_string(ignored_.size() + 1),
           std::string(n)});
      excluded_depth_ = 1;
      return;
    }
    const bool object = n == "Building" || n == "BuildingPart" || n == "TINRelief";
    const bool polygon = n == "Polygon" || n == "Triangle" || n == "Rectangle";
    if (const char* id = attribute(attributes, "id"); id != nullptr && !object && !polygon) {
      // A surface, a solid or a thematic surface an xlink may name: the polygons inside it.
      groups_.push_back({id, polygons_.size(), names_.size()});
    }
    if (object) {
      GmlObject o;
      const char* id = attribute(attributes, "id");
      o.id = id != nullptr ? id : "building-" + std::to_string(objects_.size() + 1);
      if (ids_.count(o.id) != 0) o.id += "#" + std::to_string(objects_.size() + 1);
      ids_.insert({o.id, objects_.size()});
      o.type = std::string(n);
      if (!object_stack_.empty()) o.parent = object_stack_.back();
      objects_.push_back(std::move(o));
      object_stack_.push_back(objects_.size() - 1);
      object_depth_.push_back(names_.size());
      if (n == "TINRelief") {  // its triangles (gml:Triangle patches) are the terrain's
        contexts_.push_back({1, ""});
        context_depth_.push_back(names_.size());
      }
      return;
    }
    if (is_thematic_surface(n)) {
      semantic_stack_.emplace_back(n);
      return;
    }
    if (const std::optional<int> lod = lod_property(n)) {
      contexts_.push_back({*lod, semantic_stack_.empty() ? "" : semantic_stack_.back()});
      context_depth_.push_back(names_.size());
      add_reference(attributes);  // <bldg:lod2Solid xlink:href="#..."/>
      return;
    }
    if (polygon) {
      polygons_.emplace_back();
      if (!semantic_stack_.empty()) polygons_.back().semantic = semantic_stack_.back();
      if (const char* id = attribute(attributes, "id"))
        surface_ids_.insert({id, {polygons_.size() - 1, polygons_.size()}});
      open_polygons_.push_back(polygons_.size() - 1);
      return;
    }
    if (n == "LinearRing") {
      ring_.clear();
      ring_problem_.clear();
      return;
    }
    if (n == "posList" || n == "pos" || n == "coordinates" || n == "measuredHeight") {
      collecting_ = true;
      text_.clear();
      return;
    }
    // Generic attributes (for --payload): <gen:stringAttribute name="k"><gen:value>v</...> in
    // CityGML 1.0/2.0, <gen:StringAttribute><gen:name>k</gen:name><gen:value>v</...> in 3.0.
    if (n.size() > 9 && n.substr(n.size() - 9) == "Attribute" && !object_stack_.empty() &&
        !generic_) {
      const char* key = attribute(attributes, "name");
      generic_ = Generic{key != nullptr ? key : "", "", names_.size()};
      return;
    }
    if (generic_ && (n == "name" || n == "value")) {
      collecting_ = true;
      text_.clear();
      return;
    }
    add_reference(attributes);
  }

  // An xlink:href inside a geometry property: a member of the current object's geometry at that
  // LoD, resolved once the whole file is read (it may name something further on).
  void add_reference(const char** attributes) {
    const char* href = attribute(attributes, "href");
    if (href == nullptr || contexts_.empty() || object_stack_.empty()) return;
    std::string ref = href;
    if (!ref.empty() && ref.front() == '#') ref.erase(0, 1);
    Member m;
    m.lod = contexts_.back().lod;
    m.semantic = contexts_.back().semantic;
    m.href = std::move(ref);
    objects_[object_stack_.back()].members.push_back(std::move(m));
  }

  void end(std::string_view n) {
    const int dimension = dimension_stack_.back();
    dimension_stack_.pop_back();
    const std::size_t depth = names_.size();
    names_.pop_back();
    if (excluded_depth_ > 0) {
      --excluded_depth_;
      return;
    }
    if (!groups_.empty() && groups_.back().depth == depth) {
      if (polygons_.size() > groups_.back().first)
        surface_ids_.insert({groups_.back().id, {groups_.back().first, polygons_.size()}});
      groups_.pop_back();
    }
    if (!object_depth_.empty() && object_depth_.back() == depth) {
      object_stack_.pop_back();
      object_depth_.pop_back();
      if (!context_depth_.empty() && context_depth_.back() == depth) {
        contexts_.pop_back();
        context_depth_.pop_back();
      }
      return;
    }
    if (is_thematic_surface(n)) {
      if (!semantic_stack_.empty()) semantic_stack_.pop_back();
      return;
    }
    if (!context_depth_.empty() && context_depth_.back() == depth) {
      contexts_.pop_back();
      context_depth_.pop_back();
      return;
    }
    if (n == "posList" || n == "pos" || n == "coordinates") {
      collecting_ = false;
      read_points(n == "coordinates", dimension);
      return;
    }
    if (generic_ && (n == "name" || n == "value")) {
      collecting_ = false;
      (n == "name" ? generic_->key : generic_->value) = trimmed(text_);
      return;
    }
    if (generic_ && generic_->depth == depth) {
      if (!generic_->key.empty())
        objects_[object_stack_.back()].attributes.push_back({generic_->key, generic_->value});
      generic_.reset();
      return;
    }
    if (n == "measuredHeight") {
      collecting_ = false;
      char* stop = nullptr;
      const double h = std::strtod(text_.c_str(), &stop);
      if (stop != text_.c_str() && !object_stack_.empty())
        objects_[object_stack_.back()].measured_height = h;
      return;
    }
    if (n == "LinearRing") {
      if (!open_polygons_.empty()) {
        GmlPolygon& polygon = polygons_[open_polygons_.back()];
        // CityGML closes a ring by repeating its first point; CityJSON does not.
        if (ring_.size() > 1 && ring_.front() == ring_.back()) ring_.pop_back();
        if (ring_problem_.empty()) {
          polygon.rings.push_back(std::move(ring_));
        } else {
          polygon.unreadable = true;
          std::string& why = objects_[object_stack_.back()].unreadable;
          if (why.empty()) why = "a ring's coordinates cannot be read: " + ring_problem_;
        }
      }
      ring_.clear();
      ring_problem_.clear();
      return;
    }
    if (n == "Polygon" || n == "Triangle" || n == "Rectangle") {
      const std::size_t index = open_polygons_.back();
      open_polygons_.pop_back();
      if (!contexts_.empty() && !object_stack_.empty() && !polygons_[index].unreadable) {
        Member m;
        m.lod = contexts_.back().lod;
        m.semantic = contexts_.back().semantic;
        m.polygon = index;
        objects_[object_stack_.back()].members.push_back(std::move(m));
      }
    }
  }

  // Coordinates of a posList or pos ("x y z x y z ...") or of GML 2's coordinates
  // ("x,y,z x,y,z ..."), `dimension` values per point.
  void read_points(bool comma_tuples, int dimension) {
    if (comma_tuples) std::replace(text_.begin(), text_.end(), ',', ' ');
    if (dimension != 2 && dimension != 3) {
      ring_problem("srsDimension " + std::to_string(dimension) + " (2 or 3 expected)");
      return;
    }
    std::vector<double> values;
    const char* s = text_.c_str();
    for (;;) {
      while (*s != '\0' && std::isspace(static_cast<unsigned char>(*s))) ++s;
      if (*s == '\0') break;
      char* stop = nullptr;
      const double v = std::strtod(s, &stop);
      if (stop == s) {
        ring_problem("coordinate list holds \"" +
                     std::string(s, std::min<std::size_t>(20, std::strlen(s))) +
                     "\", not a number");
        return;
      }
      values.push_back(v);
      s = stop;
    }
    if (values.size() % static_cast<std::size_t>(dimension) != 0) {
      ring_problem(std::to_string(values.size()) + " coordinates are no whole number of " +
                   std::to_string(dimension) + "D points");
      return;
    }
    for (std::size_t i = 0; i < values.size(); i += static_cast<std::size_t>(dimension))
      ring_.push_back({values[i], values[i + 1], dimension == 3 ? values[i + 2] : 0.0});
  }

  // A ring of a building that cannot be read: its polygon is left out and the building kept as
  // an object that occludes nothing (GmlObject::unreadable). Outside a building's polygon ring
  // (a TIN relief's triangle, an envelope) it is refused, as before.
  void ring_problem(const std::string& what) {
    if (object_stack_.empty() || open_polygons_.empty() || names_.empty() ||
        names_.back() != "LinearRing") {
      fail(InputProblem::BadStructure, current_id(), what);
      return;
    }
    if (ring_problem_.empty()) ring_problem_ = what;
  }

  // The CityJSON document: version 1.0, whose vertices are plain coordinates (no transform, so
  // nothing is rounded), one MultiSurface per LoD and object.
  Json document() {
    Json doc;
    doc["type"] = "CityJSON";
    doc["version"] = "1.0";
    if (!crs_.empty()) doc["metadata"]["referenceSystem"] = crs_;
    // GML writes coordinates in the axis order of the reference system: latitude first for
    // EPSG:4326, 4979 and the other geographic systems of the EPSG catalogue (JGD2011's 6697 in
    // Japan's PLATEAU models; OGC:CRS84 is longitude first), where CityJSON has x = longitude.
    if (!crs_.empty() && crs_.find("CRS84") == std::string::npos) {
      try {
        latitude_first_ = latitude_first(normalise_crs(crs_, file_));
      } catch (const InputError&) {  // the CityJSON reader names an unknown system itself
      }
    }
    Json& city_objects = doc["CityObjects"] = Json::object();
    Json vertices = Json::array();
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      const GmlObject& o = objects_[i];
      Json obj;
      obj["type"] = o.type;
      if (o.measured_height) obj["attributes"]["measuredHeight"] = *o.measured_height;
      if (!o.unreadable.empty()) obj[kUnreadableMember] = o.unreadable;
      for (const auto& [key, value] : o.attributes) obj["attributes"][key] = value;
      if (o.parent) obj["parents"] = Json::array({objects_[*o.parent].id});
      Json children = Json::array();
      for (const GmlObject& c : objects_)
        if (c.parent && *c.parent == i) children.push_back(c.id);
      if (!children.empty()) obj["children"] = std::move(children);
      obj["geometry"] = geometries(o, vertices);
      city_objects[o.id] = std::move(obj);
    }
    for (const auto& [id, type] : ignored_)
      if (!city_objects.contains(id)) city_objects[id] = Json{{"type", type}};
    doc["vertices"] = std::move(vertices);
    return doc;
  }

  static constexpr std::size_t kMaxExpansion = 16;

  Json geometries(const GmlObject& o, Json& vertices) {
    std::map<int, std::vector<std::pair<std::size_t, std::string>>> by_lod;  // polygon, semantic
    std::map<int, std::unordered_set<std::size_t>> taken;                    // per LoD
    for (const Member& m : o.members) {
      std::pair<std::size_t, std::size_t> range;  // the polygons it stands for
      if (m.polygon) {
        range = {*m.polygon, *m.polygon + 1};
      } else {
        const auto it = surface_ids_.find(m.href);
        if (it == surface_ids_.end()) continue;  // a reference to nothing with polygons
        range = it->second;
      }
      // An xlink may name a surface of any size, and any number of xlinks may name it: a few
      // bytes would stand for millions of polygons. Each polygon is written about once or
      // twice by real data; far more is refused.
      expanded_ += range.second - range.first;
      if (expanded_ > kMaxExpansion * (polygons_.size() + 1000))
        throw InputError(InputProblem::BadStructure, file_, o.id,
                         "xlinks name the file's polygons more than " +
                             std::to_string(kMaxExpansion) + " times over");
      for (std::size_t index = range.first; index < range.second; ++index) {
        if (!taken[m.lod].insert(index).second) continue;
        const std::string& semantic =
            !polygons_[index].semantic.empty() ? polygons_[index].semantic : m.semantic;
        by_lod[m.lod].push_back({index, semantic});
      }
    }
    Json out = Json::array();
    for (const auto& [lod, list] : by_lod) {
      Json boundaries = Json::array(), surfaces = Json::array(), values = Json::array();
      std::map<std::string, std::size_t> surface_of;
      for (const auto& [index, semantic] : list) {
        const GmlPolygon& p = polygons_[index];
        if (p.rings.empty()) continue;
        Json surface = Json::array();
        for (const Ring& r : p.rings) {
          Json ring = Json::array();
          for (const Point& v : r) {
            ring.push_back(vertices.size());
            vertices.push_back(latitude_first_ ? Json::array({v[1], v[0], v[2]})
                                               : Json::array({v[0], v[1], v[2]}));
          }
          surface.push_back(std::move(ring));
        }
        boundaries.push_back(std::move(surface));
        if (semantic.empty()) {
          values.push_back(nullptr);
        } else {
          auto [it, added] = surface_of.insert({semantic, surface_of.size()});
          if (added) surfaces.push_back(Json{{"type", semantic}});
          values.push_back(it->second);
        }
      }
      if (boundaries.empty()) continue;
      Json g;
      g["type"] = "MultiSurface";
      g["lod"] = lod;
      g["boundaries"] = std::move(boundaries);
      if (!surfaces.empty()) {
        g["semantics"]["surfaces"] = std::move(surfaces);
        g["semantics"]["values"] = std::move(values);
      }
      out.push_back(std::move(g));
    }
    return out;
  }

  const std::string& file_;
  XML_Parser parser_ = nullptr;
  std::optional<InputError> error_;
  std::exception_ptr pending_;
  std::vector<std::string> names_;  // open elements
  std::vector<int> dimension_stack_;
  std::string crs_;
  std::vector<GmlObject> objects_;
  std::vector<std::pair<std::string, std::string>> ignored_;  // id, type
  std::unordered_map<std::string, std::size_t> ids_;
  std::vector<std::size_t> object_stack_, object_depth_;
  std::vector<std::string> semantic_stack_;
  std::vector<Context> contexts_;
  std::vector<std::size_t> context_depth_;
  std::vector<GmlPolygon> polygons_;
  struct Group {  // an element with a gml:id still open, and the first polygon inside it
    std::string id;
    std::size_t first, depth;
  };
  std::vector<Group> groups_;
  std::size_t expanded_ = 0;  // polygons written for members, summed over the file
  /// gml:id -> the polygons [first, end) of that polygon, surface, solid or thematic surface.
  std::unordered_map<std::string, std::pair<std::size_t, std::size_t>> surface_ids_;
  std::vector<std::size_t> open_polygons_;
  Ring ring_;
  std::string ring_problem_;  ///< why ring_ cannot be read (ring_problem), or empty
  int excluded_depth_ = 0;
  bool collecting_ = false;
  struct Generic {  // a generic attribute being read
    std::string key, value;
    std::size_t depth;
  };
  std::optional<Generic> generic_;
  bool latitude_first_ = false;  // the reference system's axes are latitude, longitude
  std::string text_;
};

}  // namespace

bool is_xml(std::string_view text) {
  std::size_t i = 0;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") i = 3;  // a UTF-8 byte order mark
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  return i < text.size() && text[i] == '<';
}

Json citygml_to_cityjson(std::string_view text, const std::string& file) {
  return CityGmlParser(file).parse(text);
}

}  // namespace urbanpvs::geometry::detail
