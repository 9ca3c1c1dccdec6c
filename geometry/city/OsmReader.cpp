// SPDX-License-Identifier: GPL-3.0-or-later
// OpenStreetMap input (PBF, XML) with libosmium. Buildings and building parts come from closed
// ways and from multipolygon relations, assembled by osmium's area assembler (which also
// repairs what it can and reports the rest per object). Each area is handed on as a GeoJSON
// feature in lon/lat, with the element's tags as properties and "w123" / "r456" as its id, so
// heights (height, min_height, building:levels, roof:*), parts joining their building,
// ring repair and the local frame follow exactly the GeoJSON reader's rules.
//
// Where people can be (for --cells streets) is collected in the same pass: highway=* lines
// with their width tags, and street areas (area:highway=*, pedestrian areas, place=square),
// under the document's "urbanpvs:streets" member; OsmStreets.cpp reads them into the city and
// cells/StreetRegion.cpp turns them into polygons when --cells streets asks for them.
#include <cstring>
#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/area/problem_reporter_stream.hpp>
#include <osmium/handler.hpp>
#include <osmium/handler/check_order.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/object_pointer_collection.hpp>
#include <osmium/osm/box.hpp>
#include <osmium/osm/object_comparisons.hpp>
#include <osmium/relations/manager_util.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>
#include <sstream>
#include <utility>
#include <vector>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

std::string element_id(osmium::item_type type, osmium::object_id_type id) {
  return (type == osmium::item_type::way ? "w" : "r") + std::to_string(id);
}

std::string element_id(const osmium::Area& a) {
  return element_id(a.from_way() ? osmium::item_type::way : osmium::item_type::relation,
                    a.orig_id());
}

// One ring as GeoJSON positions; false when a node's location is missing from the extract.
bool ring_json(const osmium::NodeRefList& ring, Json& out) {
  out = Json::array();
  for (const osmium::NodeRef& n : ring) {
    if (!n.location().valid()) return false;
    out.push_back(Json::array({n.location().lon(), n.location().lat()}));
  }
  return true;
}

bool is_building(const osmium::TagList& tags) {
  const char* b = tags["building"];
  const char* p = tags["building:part"];
  return (b != nullptr && std::strcmp(b, "no") != 0) || (p != nullptr && std::strcmp(p, "no") != 0);
}

// An area where people walk or drive: mapped street surfaces, pedestrian zones, squares.
bool is_street_area(const osmium::TagList& tags, bool from_way) {
  if (tags.has_key("area:highway") || tags.has_tag("place", "square")) return true;
  // A closed pedestrian way is a zone only when it says so; else it is a loop of street.
  return tags.has_tag("highway", "pedestrian") && (!from_way || tags.has_tag("area", "yes"));
}

// Highway values that are no way a person is on (yet, or any more), and what is no line.
bool is_street_line(const osmium::Way& w) {
  const char* h = w.tags()["highway"];
  if (h == nullptr || w.tags().has_tag("area", "yes")) return false;
  for (const char* no :
       {"proposed", "construction", "abandoned", "disused", "razed", "no", "platform", "bus_stop",
        "elevator", "street_lamp", "services", "rest_area"})
    if (std::strcmp(h, no) == 0) return false;
  return w.nodes().size() >= 2;
}

// An outer ring and its inner rings as a GeoJSON polygon; false when a node is missing.
bool polygon_json(const osmium::Area& a, const osmium::OuterRing& outer, Json& out) {
  out = Json::array();
  Json ring;
  bool ok = ring_json(outer, ring);
  out.push_back(std::move(ring));
  for (const osmium::InnerRing& inner : a.inner_rings(outer)) {
    ok = ring_json(inner, ring) && ok;
    out.push_back(std::move(ring));
  }
  return ok;
}

// A building whose area osmium's assembler could not build (rings that touch at a point that is
// no shared node, bow-ties, spikes, ways that leave the extract, ...). It is kept, never
// dropped: a building missing from the city is missing from every PVS (a pop-in).
struct UnbuiltBuilding {
  std::string id;        // element_id's form
  Json properties;       // the element's tags
  Json polygons;         // GeoJSON MultiPolygon coordinates: lon/lat of its nodes in the extract
  std::string why_lost;  // empty: rings with every node, handed to the ring repair
};

osmium::Box ring_box(const Json& ring) {
  osmium::Box box;
  for (const Json& p : ring) box.extend(osmium::Location(p[0].get<double>(), p[1].get<double>()));
  return box;
}

// Keeps `element` when it is a building whose nodes in the extract span an area (one node, or
// nodes on a line, are what an extract's edge left of a building outside it); true when kept.
// `inner[i]`: ways[i] has the role "inner" (a multipolygon's; empty for a way).
bool keep_unbuilt(std::vector<UnbuiltBuilding>& unbuilt, const osmium::OSMObject& element,
                  const std::vector<const osmium::Way*>& ways, const std::vector<bool>& inner) {
  if (!is_building(element.tags())) return false;  // a street area that is not built: no street
  UnbuiltBuilding b;
  b.id = element_id(element.type(), element.id());
  b.properties = Json::object();
  for (const osmium::Tag& t : element.tags())
    if (std::strcmp(t.key(), "type") != 0) b.properties[t.key()] = t.value();
  bool every_node = true, every_way_closed = true;
  osmium::Box box;
  Json lines = Json::array(), outer_rings = Json::array(), inner_rings = Json::array();
  for (std::size_t i = 0; i < ways.size(); ++i) {
    if (ways[i] == nullptr) {
      every_node = false;
      continue;
    }
    Json line = Json::array();
    for (const osmium::NodeRef& n : ways[i]->nodes())
      if (n.location().valid()) {
        line.push_back(Json::array({n.location().lon(), n.location().lat()}));
        box.extend(n.location());
      } else {
        every_node = false;
      }
    if (line.empty()) continue;
    every_way_closed = every_way_closed && line.size() >= 4 && line.front() == line.back();
    (i < inner.size() && inner[i] ? inner_rings : outer_rings).push_back(line);
    lines.push_back(std::move(line));
  }
  if (!box.valid() || box.bottom_left().x() == box.top_right().x() ||
      box.bottom_left().y() == box.top_right().y())
    return false;
  // Rings with every node may cross themselves or each other, carry spikes or touch at a point
  // that is no node: the GeoJSON reader's ring repair (fill by winding) mends what it can, each
  // outer ring less every inner one being what a multipolygon means. A ring with nodes missing
  // would join the rest by chords that may cross open ground, an open way is no ring at all,
  // and a multipolygon's ways say nothing of which side is inside once they do not close up:
  // none of these may occlude (thesis 7.1).
  if (!every_node)
    b.why_lost = element.type() == osmium::item_type::relation
                     ? "members outside the extract"
                     : "nodes outside the extract: its ring is incomplete";
  else if (!every_way_closed || outer_rings.empty())
    b.why_lost = element.type() == osmium::item_type::relation ? "its member ways do not form rings"
                                                               : "an open way: no ring";
  b.polygons = Json::array();
  if (b.why_lost.empty()) {
    std::vector<osmium::Box> hole_boxes;
    for (const Json& hole : inner_rings) hole_boxes.push_back(ring_box(hole));
    for (Json& outer : outer_rings) {
      // An outer ring within an inner one is an island in a courtyard: that hole is not its.
      const osmium::Box outer_box = ring_box(outer);
      Json polygon = Json::array({std::move(outer)});
      for (std::size_t h = 0; h < inner_rings.size(); ++h)
        if (!hole_boxes[h].contains(outer_box.bottom_left()) ||
            !hole_boxes[h].contains(outer_box.top_right()))
          polygon.push_back(inner_rings[h]);
      b.polygons.push_back(std::move(polygon));
    }
  } else {  // only its box counts
    for (Json& line : lines) b.polygons.push_back(Json::array({std::move(line)}));
  }
  unbuilt.push_back(std::move(b));
  return true;
}

// osmium's assembler, constructed per area by the MultipolygonManager, and what it could not
// build kept in config_type::unbuilt (create_empty_areas is off: a failure gives no area).
class KeepingAssembler {
 public:
  struct config_type : osmium::area::AssemblerConfig {
    std::vector<UnbuiltBuilding>* unbuilt = nullptr;
  };
  explicit KeepingAssembler(const config_type& config)
      : osmium_(config), unbuilt_(*config.unbuilt) {}

  bool operator()(const osmium::Way& way, osmium::memory::Buffer& out) {
    if (osmium_(way, out)) return true;
    keep_unbuilt(unbuilt_, way, {&way}, {});
    return false;
  }
  bool operator()(const osmium::Relation& relation, const std::vector<const osmium::Way*>& ways,
                  osmium::memory::Buffer& out) {
    if (osmium_(relation, ways, out)) return true;
    std::vector<bool> inner;  // `ways` are the members the manager kept (a non-zero ref)
    for (const osmium::RelationMember& m : relation.members())
      if (m.ref() != 0) inner.push_back(std::strcmp(m.role(), "inner") == 0);
    keep_unbuilt(unbuilt_, relation, ways, inner);
    return false;
  }
  const osmium::area::area_stats& stats() const noexcept { return osmium_.stats(); }

 private:
  osmium::area::Assembler osmium_;
  std::vector<UnbuiltBuilding>& unbuilt_;
};

// Each unbuilt building as a GeoJSON feature, and, where it may not occlude, kUnreadableMember
// saying why.
void add_unbuilt(std::vector<UnbuiltBuilding>& unbuilt, Json& features) {
  for (UnbuiltBuilding& b : unbuilt) {
    Json geometry = Json::object();
    geometry["type"] = "MultiPolygon";
    geometry["coordinates"] = std::move(b.polygons);
    Json feature = Json::object();
    feature["type"] = "Feature";
    feature["id"] = b.id;
    feature["geometry"] = std::move(geometry);
    feature["properties"] = std::move(b.properties);
    if (!b.why_lost.empty()) feature[kUnreadableMember] = b.why_lost;
    features.push_back(std::move(feature));
  }
  unbuilt.clear();
}

class AreaFeatures : public osmium::handler::Handler {
 public:
  AreaFeatures(Json& features, Json& streets, std::vector<UnbuiltBuilding>& unbuilt,
               ReadReport& report, const std::string& file)
      : features_(features), streets_(streets), unbuilt_(unbuilt), report_(report), file_(file) {}

  void area(const osmium::Area& a) {
    const bool building = is_building(a.tags());
    if (!building) {
      if (is_street_area(a.tags(), a.from_way())) add_street_area(a);
      return;
    }
    Json polygons = Json::array();
    for (const osmium::OuterRing& outer : a.outer_rings()) {
      Json polygon;
      if (!polygon_json(a, outer, polygon)) {
        report_.warnings.push_back(file_ + ": " + element_id(a) +
                                   ": a node lies outside the extract; that ring is skipped");
        continue;
      }
      polygons.push_back(std::move(polygon));
    }
    if (polygons.empty()) return;  // every ring left the extract (reported above)
    if (!a.from_way()) ++report_.osm_multipolygons;
    Json properties = Json::object();
    for (const osmium::Tag& t : a.tags()) properties[t.key()] = t.value();
    Json geometry = Json::object();
    geometry["type"] = "MultiPolygon";
    geometry["coordinates"] = std::move(polygons);
    Json feature = Json::object();
    feature["type"] = "Feature";
    feature["id"] = element_id(a);
    feature["geometry"] = std::move(geometry);
    feature["properties"] = std::move(properties);
    features_.push_back(std::move(feature));
  }

  void way(const osmium::Way& w) {
    if (passed_over(w))
      report_.warnings.push_back(file_ + ": " + element_id(w.type(), w.id()) +
                                 ": building way that is no closed ring in the extract; " +
                                 (keep_unbuilt(unbuilt_, w, {&w}, {})
                                      ? "kept over its nodes there"
                                      : "skipped (its nodes there span no area)"));
    if (!is_street_line(w)) return;
    Json line;
    if (!ring_json(w.nodes(), line)) return;  // leaves the extract: the street is cut there
    Json street = Json::object();
    street["id"] = element_id(w.type(), w.id());
    street["line"] = std::move(line);
    for (const char* key : {"highway", "width", "est_width", "lanes"})
      if (const char* v = w.tags()[key]) street[key] = v;
    streets_.push_back(std::move(street));
  }

 private:
  void add_street_area(const osmium::Area& a) {
    for (const osmium::OuterRing& outer : a.outer_rings()) {
      Json polygon;
      if (!polygon_json(a, outer, polygon)) continue;
      Json street = Json::object();
      street["id"] = element_id(a);
      street["area"] = std::move(polygon);
      streets_.push_back(std::move(street));
    }
  }

  // A building way that the multipolygon manager passes over without a word: too short, open,
  // or its first or last node outside the extract.
  static bool passed_over(const osmium::Way& w) {
    if (!is_building(w.tags())) return false;
    const osmium::WayNodeList& n = w.nodes();
    return n.size() <= 3 || !n.front().location().valid() || !n.back().location().valid() ||
           n.front().location() != n.back().location();
  }

  Json& features_;
  Json& streets_;
  std::vector<UnbuiltBuilding>& unbuilt_;
  ReadReport& report_;
  const std::string& file_;
};

// The assembler's problems, one line per element and kind of problem: it reports every node of
// a way that leaves the extract, which would bury the other messages.
void report_lines(const std::string& text, const std::string& file, ReadReport& report) {
  std::istringstream lines(text);
  std::vector<std::pair<std::string, std::size_t>> seen;  // header ("... on w12 (...)"), count
  for (std::string line; std::getline(lines, line);) {
    if (line.empty()) continue;
    const std::size_t end = line.find("): ");
    const std::string header = end == std::string::npos ? line : line.substr(0, end + 1);
    if (!seen.empty() && seen.back().first == header) {
      ++seen.back().second;
      continue;
    }
    seen.emplace_back(header, 1);
  }
  for (const auto& [header, count] : seen)
    report.warnings.push_back(file + ": " + header +
                              (count > 1 ? " (" + std::to_string(count) + " times)" : ""));
}

}  // namespace

bool is_osm_file(const std::string& path) {
  for (const char* ext : {".osm.pbf", ".pbf", ".osm", ".osm.gz", ".osm.bz2"})
    if (has_extension(path, ext)) return true;
  return false;
}

namespace {

// The file's objects sorted as OSM files are (nodes, ways, relations, each by ascending id),
// each id once at its newest version. Overpass API exports are ordered by type and then by
// location ("out qt"), or give the ways before their nodes ("out body; >; out skel qt;"), and
// a file merged from several extracts repeats ids: osmium's multipolygon assembly needs the
// order (its second pass checks it), the node locations need the nodes before the ways.
struct SortedObjects {
  osmium::memory::Buffer buffer;  // holds the objects the collection points to
  osmium::ObjectPointerCollection objects;

  explicit SortedObjects(osmium::memory::Buffer&& objects_read) : buffer(std::move(objects_read)) {
    osmium::apply(buffer, objects);
    objects.sort(osmium::object_order_type_id_reverse_version{});  // newest version first
    objects.unique(osmium::object_equal_type_id{});                // keeps the first
  }
};

// Both of the assembly's passes over the file `input`, or over `sorted` when given: the
// relations first (which ways they need), then every object.
void assemble(const osmium::io::File* input, SortedObjects* sorted, Json& features, Json& streets,
              ReadReport& report, std::ostringstream& problems, const std::string& path) {
  osmium::area::ProblemReporterStream reporter(problems);
  std::vector<UnbuiltBuilding> unbuilt;
  KeepingAssembler::config_type config;
  config.problem_reporter = &reporter;
  config.create_empty_areas = false;
  config.unbuilt = &unbuilt;
  // Buildings and their parts ("building=no" is no building), and street areas.
  osmium::TagsFilter wanted(false);
  wanted.add_rule(false, "building", "no");
  wanted.add_rule(true, "building");
  wanted.add_rule(false, "building:part", "no");
  wanted.add_rule(true, "building:part");
  wanted.add_rule(true, "area:highway");
  wanted.add_rule(true, "highway", "pedestrian");
  wanted.add_rule(true, "place", "square");
  osmium::area::MultipolygonManager<KeepingAssembler> areas(config, wanted);
  if (sorted == nullptr) {
    osmium::relations::read_relations(*input, areas);  // pass 1: which ways the relations need
  } else {
    for (const osmium::OSMObject& o : sorted->objects)
      if (o.type() == osmium::item_type::relation)
        areas.relation(static_cast<const osmium::Relation&>(o));
    areas.prepare_for_lookup();
  }

  using Index = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
  // Two indexes: files saved from JOSM (and other editors) before upload number everything
  // negatively, and with an index for positive ids alone every node of theirs went missing,
  // every ring with it, and every building of the file vanished without a word.
  Index index, negative_index;
  osmium::handler::NodeLocationsForWays<Index, Index> locations(index, negative_index);
  locations.ignore_errors();  // a way leaving the extract: its rings are skipped, reported
  AreaFeatures collect(features, streets, unbuilt, report, path);
  auto assembled =
      areas.handler([&](osmium::memory::Buffer&& buffer) { osmium::apply(buffer, collect); });
  if (sorted == nullptr) {
    // The assembly checks the order of the ways only; the node locations need every node
    // before the ways, which an Overpass export with its ways first breaks without a word. So
    // the whole order is checked (out_of_order_error: read_osm sorts the file).
    osmium::handler::CheckOrder order;
    osmium::io::Reader reader(*input, osmium::io::read_meta::no);
    osmium::apply(reader, order, locations, collect, assembled);
    reader.close();
  } else {
    osmium::apply(sorted->objects.begin(), sorted->objects.end(), locations, collect, assembled);
  }
  areas.for_each_incomplete_relation([&](const osmium::relations::RelationHandle& r) {
    std::vector<const osmium::Way*> ways;
    std::vector<bool> inner;
    for (const osmium::RelationMember& m : r->members())
      if (m.type() == osmium::item_type::way) {
        ways.push_back(areas.get_member_way(m.ref()));
        inner.push_back(std::strcmp(m.role(), "inner") == 0);
      }
    const bool kept = keep_unbuilt(unbuilt, *r, ways, inner);
    report.warnings.push_back(path + ": " + element_id(r->type(), r->id()) +
                              ": multipolygon with members outside the extract; " +
                              (kept ? "kept over its ways there" : "skipped"));
  });
  add_unbuilt(unbuilt, features);
}

Json osm_document(Json features, Json streets) {
  Json doc = Json::object();
  doc["type"] = "FeatureCollection";
  doc["features"] = std::move(features);
  doc[kStreetsMember] = std::move(streets);
  return doc;
}

}  // namespace

Json read_osm(const std::string& path, ReadReport& report) {
  open_input_file(path);  // the project's own messages for a missing or unreadable file
  Json features = Json::array(), streets = Json::array();
  std::ostringstream problems;
  try {
    const osmium::io::File input(path);
    const ReadReport before = report;
    try {
      assemble(&input, nullptr, features, streets, report, problems, path);
    } catch (const osmium::out_of_order_error&) {
      // Streaming needs sorted input; anything else is read whole and sorted, from scratch.
      features = Json::array(), streets = Json::array();
      problems.str("");
      report = before;
      SortedObjects sorted(osmium::io::read_file(input, osmium::io::read_meta::yes));
      report.warnings.push_back(path +
                                ": objects not sorted by type and id (an Overpass API export?) "
                                "or repeated: read whole into memory and sorted");
      assemble(nullptr, &sorted, features, streets, report, problems, path);
    }
  } catch (const std::exception& e) {
    throw InputError(InputProblem::BadStructure, path, "",
                     std::string("not a readable OpenStreetMap file: ") + e.what());
  }
  report_lines(problems.str(), path, report);
  return osm_document(std::move(features), std::move(streets));
}

Json assemble_osm(osmium::memory::Buffer&& objects, const std::string& file, ReadReport& report) {
  Json features = Json::array(), streets = Json::array();
  std::ostringstream problems;
  SortedObjects sorted(std::move(objects));
  assemble(nullptr, &sorted, features, streets, report, problems, file);
  report_lines(problems.str(), file, report);
  return osm_document(std::move(features), std::move(streets));
}

}  // namespace urbanpvs::geometry::detail
