// SPDX-License-Identifier: GPL-3.0-or-later
// CityJSON geometry templates (CityJSON 1.1/2.0 "geometry-templates"): a GeometryInstance places
// a shared geometry by a 4x4 matrix at a reference vertex. Producers use them for repeated
// objects, which may be buildings (kiosks, garden sheds, standard houses of a development). A
// building whose geometry is an instance is a building like any other: left unread it would be
// in no cell's PVS and never drawn. So each instance becomes the template's geometry with
// vertices of its own, before anything else reads the file.
#include <array>
#include <cstdint>
#include <string>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"

namespace urbanpvs::geometry::detail {
namespace {

// Adds `offset` to every vertex index of a boundaries array, however deeply nested.
void shift_indices(Json& node, std::size_t offset) {
  if (node.is_array()) {
    for (Json& child : node) shift_indices(child, offset);
  } else if (node.is_number_unsigned()) {  // anything else is left for the reader to refuse
    node = node.get<std::uint64_t>() + std::uint64_t{offset};
  }
}

[[noreturn]] void bad(const std::string& file, const std::string& id, const std::string& what) {
  throw InputError(InputProblem::BadStructure, file, id, "GeometryInstance: " + what);
}

}  // namespace

void expand_geometry_instances(Json& doc, const std::string& file) {
  if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object()) return;  // the reader says
  const Json* templates = nullptr;
  const Json* template_vertices = nullptr;
  if (doc.contains("geometry-templates") && doc["geometry-templates"].is_object()) {
    const Json& g = doc["geometry-templates"];
    if (g.contains("templates") && g["templates"].is_array()) templates = &g["templates"];
    if (g.contains("vertices-templates") && g["vertices-templates"].is_array())
      template_vertices = &g["vertices-templates"];
  }
  if (!doc.contains("vertices") || !doc["vertices"].is_array()) return;
  Json& vertices = doc["vertices"];
  // Stored vertices are (real - translate) / scale; template vertices and matrices are real.
  std::array<double, 3> scale{1, 1, 1};
  if (doc.contains("transform") && doc["transform"].is_object() &&
      doc["transform"].contains("scale") && doc["transform"]["scale"].is_array() &&
      doc["transform"]["scale"].size() == 3)
    for (std::size_t i = 0; i < 3; ++i)
      scale[i] = json_number(doc["transform"]["scale"][i], file, "transform", "transform.scale");
  for (auto it = doc["CityObjects"].begin(); it != doc["CityObjects"].end(); ++it) {
    Json& object = it.value();
    if (!object.is_object() || !object.contains("geometry") || !object["geometry"].is_array())
      continue;
    // Buildings, their parts and installations; the trees and benches templates mostly serve
    // are no objects here, and a broken one must not cost the city.
    if (string_member(object, "type").rfind("Building", 0) != 0) continue;
    for (Json& g : object["geometry"]) {
      if (string_member(g, "type") != "GeometryInstance") continue;
      const std::string& id = it.key();
      if (templates == nullptr || template_vertices == nullptr)
        bad(file, id, "the file has no geometry-templates");
      if (!g.contains("template") || !g["template"].is_number_unsigned() ||
          g["template"].get<std::size_t>() >= templates->size())
        bad(file, id, "\"template\" is no index into the templates");
      const Json& shape = (*templates)[g["template"].get<std::size_t>()];
      if (!shape.is_object() || string_member(shape, "type") == "GeometryInstance")
        bad(file, id, "its template is no geometry");
      if (!g.contains("boundaries") || !g["boundaries"].is_array() || g["boundaries"].size() != 1 ||
          !g["boundaries"][0].is_number_unsigned() ||
          g["boundaries"][0].get<std::size_t>() >= vertices.size())
        bad(file, id, "\"boundaries\" must hold the index of its reference vertex");
      // The reference vertex by value: the placed vertices are appended to the same array, and
      // a reference into it would dangle once the array grows.
      std::array<double, 3> anchor{};
      {
        const Json& a = vertices[g["boundaries"][0].get<std::size_t>()];
        if (!a.is_array() || a.size() != 3) bad(file, id, "its reference vertex is no point");
        for (std::size_t r = 0; r < 3; ++r)
          anchor[r] = json_number(a[r], file, id, "reference vertex");
      }
      std::array<double, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
      if (g.contains("transformationMatrix")) {
        const Json& t = g["transformationMatrix"];
        if (!t.is_array() || t.size() != 16) bad(file, id, "transformationMatrix is no 16 numbers");
        for (std::size_t i = 0; i < 16; ++i)
          m[i] = json_number(t[i], file, id, "transformationMatrix");
      }
      // The template's vertices, placed: real = M·v (row-major, homogeneous) + the anchor.
      const std::size_t offset = vertices.size();
      for (const Json& v : *template_vertices) {
        if (!v.is_array() || v.size() != 3) bad(file, id, "a template vertex is no point");
        const std::array<double, 3> p{json_number(v[0], file, id, "template vertex"),
                                      json_number(v[1], file, id, "template vertex"),
                                      json_number(v[2], file, id, "template vertex")};
        Json placed = Json::array();
        for (std::size_t r = 0; r < 3; ++r) {
          const double real =
              m[4 * r] * p[0] + m[4 * r + 1] * p[1] + m[4 * r + 2] * p[2] + m[4 * r + 3];
          placed.push_back(anchor[r] + real / scale[r]);
        }
        vertices.push_back(std::move(placed));
      }
      Json expanded = shape;
      if (expanded.contains("boundaries")) shift_indices(expanded["boundaries"], offset);
      g = std::move(expanded);
    }
  }
}

}  // namespace urbanpvs::geometry::detail
