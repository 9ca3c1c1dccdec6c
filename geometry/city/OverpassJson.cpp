// SPDX-License-Identifier: GPL-3.0-or-later
// OpenStreetMap data as the Overpass API gives it in JSON (`[out:json]`): the most common way to
// fetch the buildings of a neighbourhood (overpass-turbo, web maps). The elements become
// osmium objects and go through the OpenStreetMap reader's assembly (OsmReader.cpp), so tags,
// parts, multipolygons and their problems are read exactly as from an .osm file.
//
// Overpass writes geometry in two ways, and both are read:
//  - "out body" / "out skel" (with `>` for the nodes): nodes with lat/lon, ways with node ids;
//  - "out geom": a way's "geometry" gives the location of each of its "nodes" (null for one
//    outside a clipping box), and a relation's way members carry their geometry without node
//    ids; such a member becomes a way of its own, on nodes numbered above every id in the file,
//    since the assembler joins rings by their nodes' locations, not by their ids.
#include <cmath>
#include <cstdint>
#include <optional>
#include <osmium/builder/osm_object_builder.hpp>
#include <osmium/memory/buffer.hpp>
#include <osmium/osm/location.hpp>
#include <set>
#include <string>
#include <vector>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

// Ids as OSM has them, far inside 64 bits (below 2^40 today): larger ones are refused, so that
// numbering new nodes above every id cannot overflow.
constexpr std::int64_t kMaxId = std::int64_t{1} << 60;

std::optional<std::int64_t> osm_id(const Json& v) {
  if (!v.is_number_integer()) return std::nullopt;
  if (v.is_number_unsigned())
    return v.get<std::uint64_t>() < static_cast<std::uint64_t>(kMaxId)
               ? std::optional<std::int64_t>(static_cast<std::int64_t>(v.get<std::uint64_t>()))
               : std::nullopt;
  const std::int64_t id = v.get<std::int64_t>();
  return id > -kMaxId && id < kMaxId ? std::optional<std::int64_t>(id) : std::nullopt;
}

class OverpassElements {
 public:
  OverpassElements(const Json& elements, const std::string& file)
      : elements_(elements), file_(file) {
    for (std::size_t k = 0; k < elements.size(); ++k) {
      const Json& e = elements[k];
      if (!e.is_object() || !e.contains("type") || !e["type"].is_string() || !e.contains("id") ||
          !e["id"].is_number_integer())
        fail(k, "is not an object with a \"type\" and an integer \"id\"");
      const std::int64_t id = integer(k, e["id"], "id");
      next_node_ = std::max(next_node_, id + 1);
      if (e["type"] == "way") {
        full_ways_.insert(id);
        if (e.contains("nodes") && e["nodes"].is_array())
          for (const Json& n : e["nodes"])
            next_node_ = std::max(next_node_, integer(k, n, "node id") + 1);
      }
    }
  }

  osmium::memory::Buffer objects() {
    for (std::size_t k = 0; k < elements_.size(); ++k) {
      const Json& e = elements_[k];
      const std::string& type = e["type"].get_ref<const std::string&>();
      if (type == "node")
        add_node(k, e);
      else if (type == "way")
        add_way(k, e);
      else if (type == "relation")
        add_relation(k, e);
      else
        ++others_;  // "area", "count", "timeline": no OSM data
    }
    return std::move(buffer_);
  }

  std::size_t others() const { return others_; }

 private:
  [[noreturn]] void fail(std::size_t k, const std::string& problem) const {
    throw InputError(InputProblem::BadStructure, file_, "elements[" + std::to_string(k) + "]",
                     problem);
  }

  std::int64_t integer(std::size_t k, const Json& v, const char* what) const {
    const std::optional<std::int64_t> id = osm_id(v);
    if (!id) fail(k, std::string(what) + " is not an integer below 2^60 in size: " + v.dump());
    return *id;
  }

  // A {"lat": .., "lon": ..} position; an invalid location for null (a node outside the box
  // that clipped an "out geom" query), which the assembly reports as a node outside the extract.
  osmium::Location location(std::size_t k, const Json& p) const {
    if (p.is_null()) return osmium::Location{};
    if (!p.is_object() || !p.contains("lat") || !p.contains("lon"))
      fail(k, "a position is not an object with \"lat\" and \"lon\"");
    const double lat = json_number(p["lat"], file_, "elements", "lat");
    const double lon = json_number(p["lon"], file_, "elements", "lon");
    if (!(std::abs(lat) <= 90 && std::abs(lon) <= 180))
      fail(k, "lat/lon out of range: " + p.dump());
    return osmium::Location{lon, lat};
  }

  void add_tags(std::size_t k, const Json& e, osmium::builder::Builder& parent) {
    if (!e.contains("tags")) return;
    if (!e["tags"].is_object()) fail(k, "\"tags\" is not an object");
    osmium::builder::TagListBuilder tags(parent);
    for (const auto& [key, value] : e["tags"].items())
      tags.add_tag(key, value.is_string() ? value.get_ref<const std::string&>() : value.dump());
  }

  template <class Builder>
  void set_head(std::size_t k, const Json& e, Builder& b) {
    b.set_id(integer(k, e["id"], "id"));
    b.set_version(e.contains("version") ? static_cast<osmium::object_version_type>(
                                              integer(k, e["version"], "version"))
                                        : 1);
    b.set_visible(true);
  }

  void add_node(std::size_t k, const Json& e) {
    {
      osmium::builder::NodeBuilder b(buffer_);
      set_head(k, e, b);
      b.set_location(location(k, e));
      add_tags(k, e, b);
    }
    buffer_.commit();
  }

  void add_location_node(std::int64_t id, osmium::Location where) {
    {
      osmium::builder::NodeBuilder b(buffer_);
      b.set_id(id).set_version(1).set_visible(true);
      b.set_location(where);
    }
    buffer_.commit();
  }

  void add_way(std::size_t k, const Json& e) {
    if (!e.contains("nodes") || !e["nodes"].is_array())
      fail(k,
           "way without a \"nodes\" array: the query wrote no geometry (\"out tags\", \"out "
           "center\"); write it with \"out geom;\" or \"out body; >; out skel qt;\"");
    const Json& nodes = e["nodes"];
    if (e.contains("geometry")) {  // "out geom": the nodes' locations, in order
      const Json& g = e["geometry"];
      if (!g.is_array() || g.size() != nodes.size())
        fail(k, "way \"geometry\" does not give one position per node");
      for (std::size_t i = 0; i < nodes.size(); ++i)
        if (const osmium::Location at = location(k, g[i]); at.valid())
          add_location_node(integer(k, nodes[i], "node id"), at);
    }
    {
      osmium::builder::WayBuilder b(buffer_);
      set_head(k, e, b);
      {
        osmium::builder::WayNodeListBuilder refs(b);
        for (const Json& n : nodes) refs.add_node_ref(integer(k, n, "node id"));
      }
      add_tags(k, e, b);
    }
    buffer_.commit();
  }

  // A way member given by its geometry alone ("out geom" of a relation): a way on new nodes.
  void add_member_way(std::size_t k, std::int64_t id, const Json& geometry) {
    if (!geometry.is_array()) fail(k, "member \"geometry\" is not an array");
    std::vector<std::int64_t> ids;
    for (const Json& p : geometry) {
      const osmium::Location at = location(k, p);
      ids.push_back(next_node_++);
      if (at.valid()) add_location_node(ids.back(), at);
    }
    {
      osmium::builder::WayBuilder b(buffer_);
      b.set_id(id).set_version(1).set_visible(true);
      osmium::builder::WayNodeListBuilder refs(b);
      for (std::int64_t n : ids) refs.add_node_ref(n);
    }
    buffer_.commit();
    full_ways_.insert(id);
  }

  void add_relation(std::size_t k, const Json& e) {
    if (!e.contains("members") || !e["members"].is_array())
      fail(k, "relation without a \"members\" array");
    const Json& members = e["members"];
    for (const Json& m : members) {
      if (!m.is_object() || !m.contains("type") || !m["type"].is_string() || !m.contains("ref"))
        fail(k, "a member is not an object with \"type\" and \"ref\"");
      const std::int64_t ref = integer(k, m["ref"], "member ref");
      if (m["type"] == "way" && m.contains("geometry") && !full_ways_.count(ref))
        add_member_way(k, ref, m["geometry"]);
    }
    {
      osmium::builder::RelationBuilder b(buffer_);
      set_head(k, e, b);
      {
        osmium::builder::RelationMemberListBuilder list(b);
        for (const Json& m : members) {
          const std::string& type = m["type"].get_ref<const std::string&>();
          const osmium::item_type t = type == "node"  ? osmium::item_type::node
                                      : type == "way" ? osmium::item_type::way
                                                      : osmium::item_type::relation;
          const std::string role = string_member(m, "role");
          list.add_member(t, integer(k, m["ref"], "member ref"), role);
        }
      }
      add_tags(k, e, b);
    }
    buffer_.commit();
  }

  const Json& elements_;
  const std::string& file_;
  osmium::memory::Buffer buffer_{std::size_t{1} << 20, osmium::memory::Buffer::auto_grow::yes};
  std::set<std::int64_t> full_ways_;  ///< ways given whole, and member ways made so far
  std::int64_t next_node_ = 1;        ///< above every id of the file
  std::size_t others_ = 0;
};

}  // namespace

bool is_overpass_json(const Json& doc) {
  return doc.is_object() && !doc.contains("type") && doc.contains("elements") &&
         doc["elements"].is_array();
}

Json read_overpass_json(const Json& doc, const std::string& file, ReadReport& report) {
  OverpassElements elements(doc["elements"], file);
  osmium::memory::Buffer objects{0};
  try {
    objects = elements.objects();
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {  // osmium's limits: a tag or role of over 256 bytes
    throw InputError(InputProblem::BadStructure, file, "elements", e.what());
  }
  // The API says why a result is cut short ("runtime error: Query timed out ...") in a remark.
  if (const std::string remark = string_member(doc, "remark"); !remark.empty())
    report.warnings.push_back(file + ": the Overpass API remarks: " + remark);
  if (elements.others() > 0)
    report.warnings.push_back(file + ": " + std::to_string(elements.others()) +
                              " element(s) that are no node, way or relation left out");
  return assemble_osm(std::move(objects), file, report);
}

}  // namespace urbanpvs::geometry::detail
