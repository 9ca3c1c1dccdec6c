// SPDX-License-Identifier: GPL-3.0-or-later
// Everything the per-cell visibility work reads, built once from the city and shared read-only
// by every thread (thesis 5.2.4): blocks, occluders shrunk by ε, view cells with their samples,
// the area the cull maps cover, and quadtrees of objects and occluders. Data flows one way:
// city → blocks/occluders → view cells → (per cell) cull maps → PVS.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/cells/ViewCells.hpp"
#include "urbanpvs/geometry/occluders/Blocks.hpp"
#include "urbanpvs/geometry/occluders/Occluder.hpp"
#include "urbanpvs/preprocess/bake/CompactPvsStore.hpp"
#include "urbanpvs/preprocess/visibility/CellMapRenderer.hpp"
#include "urbanpvs/preprocess/visibility/CullMap.hpp"
#include "urbanpvs/preprocess/visibility/SpatialIndex.hpp"
#include "urbanpvs/preprocess/visibility/TerrainPyramid.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::preprocess {

enum class Method { Hierarchical, BruteForce };

/// One settings struct for the whole bake; stored in the output (thesis 7.2 couples ε and the
/// pixel size: CullMapSettings::validate).
struct BakeOptions {
  geometry::BlockOptions blocks;
  geometry::ViewCellOptions cells;  ///< cells.epsilon is the ε of shrinking and sampling
  double pixel = 1.39;              ///< cull-map pixel size [Units: m] [Limit: <= max_pixel(ε)]
  Backend backend = Backend::Cpu;
  Method method = Method::Hierarchical;
  /// Side of the first cull map of the hierarchical test [Units: pixels] [Limit: 8 .. 65536].
  /// 32 pixels (45 m at the default pixel) hold an 18 m cell with room around it; beyond them
  /// the samples' horizons judge as the map would, at a fraction of its cost (README,
  /// "Smaller maps": 128-pixel maps took 1.06-3.7x the time for the same mean PVS).
  int initial_map = 32;
  /// Largest cull map side [Units: pixels] [Limit: initial_map .. 65536]. Maps grow ×2 up to
  /// it; what is still undecided beyond it is decided by the samples' horizons (SampleHorizon),
  /// which cost far less than large maps and lose almost nothing against them. 65536: maps
  /// alone, grown until they cover the city (the thesis's form).
  int max_map = 32;
  /// The samples' horizons take an occluder at least kFarOutlineRatio times this away by its
  /// outline with corners cut inwards by up to this (geometry::simplified_inward; 0: exact
  /// outlines) [Units: m] [Limit: 0 .. 10]. A part of an occluder hides no more than the whole,
  /// so the far field stays conservative; it adds fewer walls (README, "Far outlines": the 3D
  /// BAG tile 1.31x faster, the same PVS on every city measured).
  double far_outline_tolerance = 1;
  /// Seen from kFarOutlineRatio × far_outline_tolerance or farther, a cut moves an outline by at
  /// most 1/60 rad: about 3 of the horizon's 1,024 sectors (SampleHorizon::kBins).
  static constexpr int kFarOutlineRatio = 60;
  /// Occluders are shrunk by this instead of cells.epsilon. Only for tests that must show a
  /// broken bake is caught (urbanpvs-validate); never set it otherwise. [Units: m]
  double shrink_override = -1;

  /// Throws std::invalid_argument naming the value to change.
  void validate() const;
};

class BakeScene {
 public:
  /// Throws std::invalid_argument for invalid options (geometry errors propagate). `threads`
  /// share the scene's own work (the roof faces' occluders, block by block); the scene is the
  /// same for any number.
  BakeScene(const geometry::City& city, const BakeOptions& options, unsigned threads = 1);

  const geometry::City& city() const { return *city_; }
  const BakeOptions& options() const { return options_; }
  const std::vector<geometry::Block>& blocks() const { return blocks_; }
  const std::vector<geometry::Occluder>& occluders() const { return occluders_; }
  /// With --solid-step: the buildings the 3D route gave occluders, and why it gave the others
  /// none (reason -> buildings).
  std::size_t solids_shrunk() const { return solids_shrunk_; }
  const std::map<std::string, std::size_t>& solids_declined() const { return solids_declined_; }
  /// Occluder `id` as a sample's horizon takes it from ground distance `distance`: from
  /// BakeOptions::kFarOutlineRatio × far_outline_tolerance on, with its outline simplified
  /// inwards (a polygon inside the occluder, fewer walls to add); nearer, the occluder itself.
  const geometry::Occluder& horizon_occluder(std::uint32_t id, double distance) const {
    return distance >= far_outline_distance_ ? far_occluders_[id] : occluders_[id];
  }
  /// The terrain's sloped squares (--terrain-planes) merged into coarser ones, for the
  /// horizons; empty without them.
  const TerrainPyramid& terrain_pyramid() const { return terrain_pyramid_; }
  /// Whether occluder `id` is one of the terrain's sloped squares (the pyramid's grid).
  bool is_terrain_square(std::uint32_t id) const {
    return id >= terrain_squares_.first && id < terrain_squares_.second;
  }
  const geometry::ViewCellMesh& mesh() const { return mesh_; }
  std::size_t cell_count() const { return mesh_.cells.size(); }

  /// The pixel lattice every cull map is cut from, covering the cells and every building.
  const CullMapGrid& area() const { return area_; }
  double zlo() const { return zlo_; }  ///< below every object
  double zhi() const { return zhi_; }  ///< above every occluder
  const BoxQuadtree& object_index() const { return object_index_; }
  /// Object i's ground outline, the pixels a cull map tests it over (geometry::object_outline).
  const std::vector<geometry::Ring>& object_outlines() const { return object_outlines_; }
  const BoxQuadtree& occluder_index() const { return occluder_index_; }

  /// The samples of a cell: those of its three top edges (thesis 5.3), each point once.
  std::vector<Vec3> samples(std::uint32_t cell) const;
  /// The one assembly of the output file, for bake_city and urbanpvs-preprocess alike: frame
  /// and settings of this scene, the objects in city order, cell i with `pvs[i]` (one per cell),
  /// and `properties` stored as given: bake_properties() of the options, then whatever the
  /// caller adds (urbanpvs-preprocess: its version, reading options, region and inputs).
  runtime::PvsBake pvs_file(std::vector<std::vector<std::uint32_t>> pvs,
                            std::vector<std::pair<std::string, std::string>> properties,
                            std::uint64_t input_hash = 0) const;
  /// The same file with the lists held compactly (a large bake's): the bake reads them from
  /// `pvs` as it is encoded (runtime::PvsBake::pvs_source), so `pvs` must outlive it. The bytes
  /// encoded are those of the lists given as vectors.
  runtime::PvsBake pvs_file(const CompactPvsStore& pvs,
                            std::vector<std::pair<std::string, std::string>> properties,
                            std::uint64_t input_hash = 0) const;
  runtime::PvsBake pvs_file(CompactPvsStore&& pvs,
                            std::vector<std::pair<std::string, std::string>> properties,
                            std::uint64_t input_hash = 0) const = delete;  // it would dangle

 private:
  /// The file less its lists, for `lists` of them (std::invalid_argument unless one per cell).
  runtime::PvsBake pvs_file_without_lists(
      std::size_t lists, std::vector<std::pair<std::string, std::string>> properties,
      std::uint64_t input_hash) const;
  runtime::CellRecord cell_record(std::uint32_t cell) const;  ///< its list left empty

  const geometry::City* city_;
  BakeOptions options_;
  std::vector<geometry::Block> blocks_;
  std::vector<geometry::Occluder> occluders_;
  std::size_t solids_shrunk_ = 0;
  std::map<std::string, std::size_t> solids_declined_;
  std::vector<geometry::Occluder> far_occluders_;  ///< same order; empty: tolerance 0
  /// From here on the horizons take far_occluders_ (infinity: tolerance 0, none built).
  double far_outline_distance_ = std::numeric_limits<double>::infinity();
  geometry::ViewCellMesh mesh_;
  CullMapGrid area_;
  double zlo_ = 0, zhi_ = 0;
  BoxQuadtree object_index_, occluder_index_;
  std::pair<std::uint32_t, std::uint32_t> terrain_squares_{0, 0};  ///< occluders_[first, second)
  TerrainPyramid terrain_pyramid_;
  std::vector<geometry::Ring> object_outlines_;
};

}  // namespace urbanpvs::preprocess
