// SPDX-License-Identifier: GPL-3.0-or-later
// Assembles view cells (thesis 5.3) from the refined free-space triangulation: ground heights,
// eye band, adjacency, the global edge list and the top-edge samples.
#include "urbanpvs/geometry/cells/ViewCells.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "BoundarySimplification.hpp"
#include "FreeSpaceTriangulation.hpp"
#include "urbanpvs/geometry/cells/GroundHeight.hpp"
#include "urbanpvs/geometry/cells/StreetRegion.hpp"
#include "urbanpvs/geometry/cells/ViewCellSamples.hpp"
#include "urbanpvs/geometry/cells/ViewCellSettings.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

bool lexicographically_less(Vec2 a, Vec2 b) {
  return a.x < b.x || (a.x == b.x && a.y < b.y);
}

Polygon rectangle(const Box2& b) {
  return {b.corners(), {}};
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Free space as a viewer meets it, not as the data's noise draws it (thesis 5.3). Real
// footprints overlap by a few cm, leave walls a few mm apart and repeat vertices a mm apart;
// meshed as they are, each of those features is refined into cells as small as itself. Grown
// by gap/2 (walls closer than the block gap tolerance merge, as in the blocks), fused exactly,
// then grown by snap more and simplified within snap: the result still contains every
// footprint (the simplification moves no boundary by more than snap), so no cell enters a
// building, and no two of its features are closer than the tolerances.
std::vector<Polygon> cleaned_obstacles(const City& city, const ViewCellOptions& options) {
  const double grow = 0.5 * options.gap + options.snap;
  std::vector<Polygon> grown;
  for (const CityObject& o : city.objects)
    for (Polygon p : o.footprint) {
      // Footprints built by hand may run either way; offsets and unions need outer CCW,
      // holes CW.
      if (signed_area2(p.outer) < 0) std::reverse(p.outer.begin(), p.outer.end());
      for (Ring& h : p.holes)
        if (signed_area2(h) > 0) std::reverse(h.begin(), h.end());
      if (!(grow > 0)) {
        grown.push_back(p);
        continue;
      }
      for (Polygon& g : grow_polygon(p, grow)) grown.push_back(std::move(g));
    }
  if (grown.empty()) return grown;
  return detail::simplify_boundaries(union_polygons(grown), options.snap);
}

}  // namespace

void validate(const ViewCellOptions& o) {
  // The limits are the settings table's, the ones the command lines enforce.
  check_limits(view_cell_settings(), o);
  for (std::size_t i = 0; i < o.region.size(); ++i) {
    bool finite = true;
    for_each_edge(o.region[i], [&](Vec2 a, Vec2) { finite = finite && std::isfinite(a.x + a.y); });
    if (!finite)
      throw std::invalid_argument("ViewCellOptions.region[" + std::to_string(i) +
                                  "]: non-finite coordinate");
    if (std::string why = polygon_defect(o.region[i]); !why.empty())
      throw std::invalid_argument("ViewCellOptions.region[" + std::to_string(i) + "]: " + why);
  }
}

double min_angle_deg(const std::array<Vec2, 3>& t) {
  double smallest = 180;
  for (std::size_t k = 0; k < 3; ++k) {
    const Vec2 u = t[(k + 1) % 3] - t[k], v = t[(k + 2) % 3] - t[k];
    smallest = std::min(smallest, std::atan2(std::abs(cross(u, v)), dot(u, v)));
  }
  return std::min(180.0, smallest * 180.0 / std::numbers::pi);
}

ViewCellMesh build_view_cells(const City& city, const ViewCellOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  validate(options);
  ViewCellMesh mesh;
  mesh.options = options;
  // Stored like footprints (outer CCW, holes CW), so the region used can go on to Boolean
  // operations as it is.
  for (Polygon& r : mesh.options.region) {
    if (signed_area2(r.outer) < 0) std::reverse(r.outer.begin(), r.outer.end());
    for (Ring& h : r.holes)
      if (signed_area2(h) > 0) std::reverse(h.begin(), h.end());
  }
  if (options.placement == ViewCellOptions::Placement::File && mesh.options.region.empty())
    throw std::invalid_argument("ViewCellOptions.placement: --cells " + options.region_file +
                                ", but no region was read from it (read_region_file)");
  if (options.placement == ViewCellOptions::Placement::Streets) {
    if (!mesh.options.region.empty())
      throw std::invalid_argument(
          "ViewCellOptions.placement: --cells streets and a region (--region) exclude each "
          "other");
    mesh.options.region = street_region(city.streets);
    if (mesh.options.region.empty())
      throw std::invalid_argument(
          "ViewCellOptions.placement: --cells streets, but the input maps no streets "
          "(OpenStreetMap highway=*, area:highway=*, pedestrian areas, place=square)");
  }
  if (mesh.options.region.empty()) {
    // Within `margin` of some building: for a dense city its bounding rectangle, for
    // scattered data (49 Zürich buildings over 10 km) the neighbourhoods of the buildings
    // alone, not 90 km² of fields between them.
    std::vector<Polygon> near;
    for (const CityObject& o : city.objects)
      if (!o.bbox.xy.empty()) near.push_back(rectangle(o.bbox.xy.grown(options.margin)));
    if (near.empty())
      throw std::invalid_argument(
          "ViewCellOptions.region: the city has no buildings to take a default region from");
    // The union of the rectangles is a staircase whose short steps the mesher would fill with
    // small cells; within a fifth of the margin its outline does just as well.
    mesh.options.region =
        options.margin > 0 ? detail::simplify_boundaries(union_polygons(near), 0.2 * options.margin)
                           : near;
  }
  Box2 region_box;
  for (const Polygon& r : mesh.options.region) region_box.extend(bounds(r));
  // Delaunay refinement makes about one cell per 0.2 max_cell_edge² (measured); keep the output
  // within what a PVS file and memory can hold.
  if (region_box.area() > 5e6 * options.max_cell_edge * options.max_cell_edge)
    throw std::invalid_argument(
        "ViewCellOptions.max_cell_edge = " + std::to_string(options.max_cell_edge) +
        " would give tens of millions of cells for this region");

  const std::vector<Polygon> cleaned = cleaned_obstacles(city, options);
  std::vector<const Polygon*> obstacles;
  for (const Polygon& p : cleaned) obstacles.push_back(&p);
  detail::FreeSpaceTriangulation tri = detail::triangulate_free_space(
      mesh.options.region, obstacles, options.max_cell_edge, kCellShapeBound,
      std::min(options.min_cell_edge, 0.5 * options.max_cell_edge), options.narrow_gap);

  const GroundModel ground(city);
  mesh.vertices = std::move(tri.vertices);
  mesh.vertex_ground.reserve(mesh.vertices.size());
  for (Vec2 v : mesh.vertices) mesh.vertex_ground.push_back(ground.at(v));

  mesh.cells.resize(tri.triangles.size());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    ViewCell& cell = mesh.cells[c];
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t v = tri.triangles[c][k];
      cell.vertex[k] = v;
      cell.corner[k] = mesh.vertices[v];
      cell.ground[k] = mesh.vertex_ground[v];
      lo = std::min(lo, cell.ground[k]);
      hi = std::max(hi, cell.ground[k]);
      mesh.bounds.extend(cell.corner[k]);
    }
    // The ground may rise inside the cell above its corners (a crest, a terrain vertex): the
    // top must clear the highest ground in it, else a viewpoint there sees over the samples.
    const auto [ground_lo, ground_hi] = ground.range_in(cell.corner);
    cell.zmin = std::min(lo, ground_lo) + options.eye_min;
    cell.zmax = std::max(hi, ground_hi) + options.eye_max;
    cell.neighbour = tri.neighbours[c];
    mesh.free_area += 0.5 * cross(cell.corner[1] - cell.corner[0], cell.corner[2] - cell.corner[0]);
  }

  // Each undirected edge once, sampled from its lexicographically smaller end, so the two cells
  // that share it get bit-identical samples (their cull maps must agree on the shared boundary).
  mesh.edges.reserve(mesh.cells.size() * 3 / 2 + 16);
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    ViewCell& cell = mesh.cells[c];
    for (std::size_t k = 0; k < 3; ++k) {
      const std::int32_t n = cell.neighbour[k];
      if (n >= 0 && std::size_t(n) < c) {
        const ViewCell& other = mesh.cells[std::size_t(n)];
        for (std::size_t j = 0; j < 3; ++j)
          if (other.neighbour[j] == std::int32_t(c)) cell.edge[k] = other.edge[j];
        continue;
      }
      std::uint32_t a = cell.vertex[(k + 1) % 3], b = cell.vertex[(k + 2) % 3];
      if (lexicographically_less(mesh.vertices[b], mesh.vertices[a])) std::swap(a, b);
      CellEdge e;
      e.vertex = {a, b};
      e.cell = {std::int32_t(c), n};
      e.first_sample = std::uint32_t(mesh.samples.size());
      // Samples sit at the top of the prism, level (thesis 5.3): from a flat top face, the face's
      // boundary sees all the interior sees (for a sight line rising to its target the
      // boundary point farthest back does, for a falling one the nearest). A top that followed
      // the ground would leave viewpoints up to zmax above the samples. An edge shared by two
      // cells takes the higher top: a higher viewpoint sees a superset over 2.5D occluders.
      const double top = n >= 0 ? std::max(cell.zmax, mesh.cells[std::size_t(n)].zmax) : cell.zmax;
      const Vec3 pa{mesh.vertices[a].x, mesh.vertices[a].y, top};
      const Vec3 pb{mesh.vertices[b].x, mesh.vertices[b].y, top};
      sample_top_edge(pa, pb, options.epsilon, mesh.samples);
      if (mesh.samples.size() > std::numeric_limits<std::uint32_t>::max())
        throw std::invalid_argument("ViewCellOptions.epsilon = " + std::to_string(options.epsilon) +
                                    " gives more than 2^32 samples");
      e.sample_count = std::uint32_t(mesh.samples.size() - e.first_sample);
      cell.edge[k] = std::uint32_t(mesh.edges.size());
      mesh.edges.push_back(e);
    }
  }

  ViewCellStats& s = mesh.stats;
  switch (ground.source()) {
    case GroundModel::Source::Terrain:
      s.ground = ViewCellStats::Ground::Terrain;
      break;
    case GroundModel::Source::Buildings:
      s.ground = ViewCellStats::Ground::Buildings;
      break;
    case GroundModel::Source::Zero:
      s.ground = ViewCellStats::Ground::Zero;
      break;
  }
  s.footprints = obstacles.size();
  s.constraint_vertices = tri.constraint_vertices;
  s.sliver_faces = tri.sliver_faces;
  s.sliver_area = tri.sliver_area;
  s.nudged_vertices = tri.nudged_vertices;
  s.unresolved_vertices = tri.unresolved_vertices;
  s.seconds_triangulation = tri.seconds_cdt;
  s.seconds_refinement = tri.seconds_refine;
  s.seconds_total = seconds_since(t0);
  return mesh;
}

}  // namespace urbanpvs::geometry
