// SPDX-License-Identifier: GPL-3.0-or-later
// View cells (thesis 5.3): free space (the street level where a viewer can stand) subdivided into
// triangular prisms by a refined constrained Delaunay triangulation. The PVS stores one object
// list per cell; the cull maps of a cell are computed from sample points on the three top edges
// of its prism (thesis 5.2.1: for 2.5D occluders, visibility from the top face's boundary bounds
// visibility from the whole prism).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::geometry {

/// Every setting of the view-cell subdivision. Checked by validate() against the limits of
/// view_cell_settings() (ViewCellSettings.hpp), the table every tool binds; they keep the output
/// size sane (cells grow with area / max_cell_edge², samples with perimeter / epsilon).
struct ViewCellOptions {
  /// Where cells go when no `region` is given: all free space near the buildings, or only
  /// where the input maps streets, squares and paths (City::streets; thesis 5.3 used
  /// street cells too). A walking or driving simulator needs no cells in backyards.
  /// File: the region comes from `region_file` (--cells FILE), which the tools read into
  /// `region` before building the cells, as for --region FILE.
  enum class Placement { Everywhere, Streets, File };
  Placement placement = Placement::Everywhere;
  /// With Placement::File: the GeoJSON (Multi)Polygons of the region (read_region_file).
  std::string region_file;
  /// Longest allowed cell edge. Smaller cells give tighter PVSs but more cells (thesis 5.3; the
  /// thesis's 8 km² Vienna model had 82,300 cells). The default gives 82,800 cells on a
  /// generated Vienna-scale city (8 km², ~2,000 blocks, seed 7). [Units: m]
  double max_cell_edge = 18.0;
  /// Bottom of the eye band above the ground. [Units: m]
  double eye_min = 0.0;
  /// Top of the eye band above the ground. A cell's prism reaches this far above the highest
  /// ground in it; its samples sit level at that top (thesis 5.3). [Units: m]
  double eye_max = 2.0;
  /// The default region (ignored when `region` is given) is everything within this margin of a
  /// building's bounding rectangle. [Units: m]
  double margin = 50.0;
  /// Sample spacing on the cells' top edges: every point of a top edge is within epsilon of a
  /// sample (thesis 5.3: samples at most 2ε apart; the occluders must be shrunk by the same ε,
  /// thesis 7.2). [Units: m]
  double epsilon = 1.0;
  /// Slivers of free space thinner than this along a wall (nearly coincident walls of
  /// neighbouring buildings: digitizing noise) are left out of the cells, instead of being
  /// refined into thousands of cells as narrow as the sliver; their area is reported in
  /// ViewCellStats::sliver_area. 0 keeps every sliver. [Units: m]
  double narrow_gap = 0.01;
  /// Footprints closer than this fuse before meshing, as they fuse into blocks (the bake sets
  /// it from BlockOptions::gap_tolerance): a gap a viewer cannot stand in gets no cells.
  /// [Units: m]
  double gap = 0.05;
  /// Clean-up tolerance of free space's boundary (thesis 5.3 meshes free space, not the
  /// data's noise): the fused footprints grow by this much, then their rings are simplified
  /// within it, so near-duplicate vertices, walls a few mm apart and wiggles smaller than it
  /// vanish while every cell stays outside every building. The default keeps a viewer's eye
  /// 0.275 m from any wall (gap/2 + snap), about half a body's width. [Units: m]
  double snap = 0.25;
  /// The mesher refines a cell for its shape only while its shortest edge is longer than this,
  /// and splits a wall piece for Gabriel conformity only while it is longer than this.
  /// Delaunay refinement chases small input angles and close features into ever smaller
  /// triangles (one real city grew past 17 GB); a badly shaped cell is still a valid cell.
  /// Measured with urbanpvs-cells: the generated 1 km² city (seed 7) gets 12,158 cells with 4, 6
  /// or 9 m; Delft's alleys 1,430 with 4 m and 1,387 with 6 m (1,640 when walls were split).
  /// Cells smaller than max_cell_edge / 2 are always refined for shape (the floor used is
  /// min(min_cell_edge, max_cell_edge / 2)). [Units: m]
  double min_cell_edge = 6.0;
  /// The region to subdivide, in the city's local frame: the union of these polygons (simple
  /// rings; orientation does not matter). Empty: street_region(city.streets) with
  /// Placement::Streets, else the union of the buildings' bounding rectangles grown by
  /// `margin`. ViewCellMesh::options holds the region used, oriented like footprints.
  std::vector<Polygon> region;
};

/// Throws std::invalid_argument naming the first option that is out of its limits.
void validate(const ViewCellOptions& options);

/// One view cell: the prism over a triangle of free space from zmin to zmax.
struct ViewCell {
  std::array<Vec2, 3> corner;           ///< counter-clockwise
  std::array<std::uint32_t, 3> vertex;  ///< corner k is ViewCellMesh::vertices[vertex[k]]
  std::array<double, 3> ground;         ///< ground height (absolute) at corner k
  double zmin = 0;                      ///< lowest ground in the cell + eye_min
  double zmax = 0;                      ///< highest ground in the cell + eye_max
  /// The cell across the edge opposite corner k (corners k+1, k+2), or -1 where that edge is a
  /// building wall or the region's boundary.
  std::array<std::int32_t, 3> neighbour;
  /// ViewCellMesh::edges index of the edge opposite corner k.
  std::array<std::uint32_t, 3> edge;
};

/// An undirected edge of the triangulation with the samples of its top edge, computed once so
/// that the cells on both sides see bit-identical samples.
struct CellEdge {
  /// Endpoints (ViewCellMesh::vertices indices), lexicographically smaller point (x, then y)
  /// first; the samples run from vertex[0] to vertex[1].
  std::array<std::uint32_t, 2> vertex;
  /// The cells on its two sides; cell[1] is -1 on a wall or the region boundary.
  std::array<std::int32_t, 2> cell;
  std::uint32_t first_sample = 0;  ///< into ViewCellMesh::samples
  std::uint32_t sample_count = 0;  ///< >= 2: both endpoints are samples
};

/// What building the cells took; for people and benchmarks.
struct ViewCellStats {
  enum class Ground { Terrain, Buildings, Zero };
  Ground ground = Ground::Zero;         ///< where ground heights came from
  std::size_t footprints = 0;           ///< footprint polygons subtracted
  std::size_t constraint_vertices = 0;  ///< triangulation vertices before refinement
  std::size_t sliver_faces = 0;         ///< thin faces left out (ViewCellOptions::narrow_gap)
  double sliver_area = 0;               ///< their area (m²): free_area + this = free space
  std::size_t nudged_vertices = 0;      ///< rounded points moved off a building by a few ulps
  std::size_t unresolved_vertices = 0;  ///< rounded points left inside a building (expected 0)
  double seconds_triangulation = 0;     ///< constrained Delaunay triangulation + classification
  double seconds_refinement = 0;        ///< Delaunay refinement (CGAL mesher) + extraction
  double seconds_total = 0;             ///< everything build_view_cells did
};

struct ViewCellMesh {
  std::vector<Vec2> vertices;
  std::vector<double> vertex_ground;  ///< ground height at each vertex (absolute)
  std::vector<ViewCell> cells;
  std::vector<CellEdge> edges;
  std::vector<Vec3> samples;  ///< of all edges; see CellEdge::first_sample
  Box2 bounds;                ///< of the cells
  double free_area = 0;       ///< summed cell area (m²)
  ViewCellOptions options;    ///< as used (region filled in when it was the default)
  ViewCellStats stats;

  std::span<const Vec3> samples_of(const CellEdge& e) const {
    return {samples.data() + e.first_sample, e.sample_count};
  }
};

/// The view cells of `city`: free space = the region minus every building footprint
/// (CityObject::footprint, grown by gap/2 + snap, fused exactly and simplified within snap:
/// ViewCellOptions::gap, snap), less slivers thinner than `narrow_gap` along walls. Triangulated
/// and refined so that
///  - no cell edge is longer than max_cell_edge;
///  - no cell angle is below kMinCellAngleDeg, except where the cell's shortest edge is below
///    min_cell_edge (near sharp corners of free space and close features);
///  - no cell overlaps a footprint's interior, decided exactly: rounded points (midpoints of
///    slanted walls, crossings of footprints) are moved by a few ulps into free space.
/// Deterministic. Throws std::invalid_argument for invalid options or when there is nothing to
/// subdivide (no buildings and no region, or far too many cells for the region).
ViewCellMesh build_view_cells(const City& city, const ViewCellOptions& options = {});

/// The mesher's shape bound: B = sin²(smallest angle) = 0.125, i.e. 20.7° (Shewchuk's bound for
/// guaranteed termination of Delaunay refinement).
inline constexpr double kCellShapeBound = 0.125;
/// asin(sqrt(kCellShapeBound)) in degrees, rounded down.
inline constexpr double kMinCellAngleDeg = 20.7;

/// The smallest interior angle of a triangle, in degrees.
double min_angle_deg(const std::array<Vec2, 3>& t);

}  // namespace urbanpvs::geometry
