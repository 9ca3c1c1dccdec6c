// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-validate's core: checks a PVS file against ray casting in the input's own surfaces
// (RayScene). From random viewpoints inside the cells (on the top face and inside the prism) it
// casts segments towards target points spread over every surface of every object missing from
// the cell's PVS (over the box of an object that does not occlude): an object whose target is
// reached is a *miss*, the worst bug a PVS can have. Cracks narrower than
// ValidationOptions::crack between blockers are closed (target_seen). It also measures
// tightness: |PVS| over the number of objects actually seen (the target segments plus a cube
// map of directions; an object a cube-map ray meets first and that is absent from the PVS is a
// miss too): per viewpoint, and per cell over several viewpoints of it (the objects seen from
// any of them, as an exact from-region PVS would hold them).
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/validate/RayScene.hpp"

namespace urbanpvs::validate {

struct ValidationOptions {
  std::size_t viewpoints = 2000;           ///< viewpoints checked for misses
  std::size_t tightness_viewpoints = 200;  ///< of those, the first n also measure tightness
  int cube_resolution = 16;                ///< rays per cube face side for tightness [1 .. 1024]
  /// Largest distance between neighbouring target points on a surface. [Units: m]
  /// [Limit: 0.1 .. 1000]
  double point_spacing = 2.0;
  /// Openings between blockers narrower than this are closed: a target counts as seen only
  /// when the segment to it and four parallel ones crack/2 to its sides (horizontally and
  /// vertically, across the segment) all reach it. The default matches the bake's default
  /// block gap tolerance (urbanpvs-preprocess --gap 0.05): gaps narrower than that between
  /// buildings are digitizing noise between shared walls, which the bake fuses too. 0: single
  /// segments, nothing closed (shared walls may then leak along their plane). A value above the
  /// bake's --gap hides real misses through openings narrower than it. [Units: m]
  /// [Limit: 0 .. 1]
  double crack = 0.05;
  std::uint64_t seed = 1;
  /// Per-cell tightness (issue 18's protocol): this many distinct random cells, each seen from
  /// viewpoints_per_cell random viewpoints of it; a cell's tightness is |PVS| over the objects
  /// seen from any of them. Their viewpoints are checked for misses too. 0: off.
  /// [Limit: 0 .. 1,000,000]
  std::size_t tightness_cells = 0;
  std::size_t viewpoints_per_cell = 8;  ///< [Limit: 1 .. 1,024]

  /// Throws std::invalid_argument naming the first value out of its limits.
  void validate() const;
};

struct Miss {
  std::uint32_t cell = 0;
  Vec3 viewpoint;
  std::uint32_t object = 0;
  std::string object_id;
  Vec3 target;  ///< the point of the object the segments reached
};

/// One cell of the per-cell tightness: its PVS size and the objects seen from any of its
/// viewpoints (all in its PVS when it has no miss).
struct CellTightness {
  std::uint32_t cell = 0;
  std::size_t pvs = 0;
  std::size_t seen = 0;
};

/// Mean, median and 90th percentile of |PVS| / seen over the cells that saw something; a cell
/// that saw nothing (open land all round, or only its own ground) has no ratio and is counted
/// apart.
struct CellTightnessStats {
  std::size_t cells = 0;  ///< cells with a ratio
  std::size_t saw_nothing = 0;
  double mean = 0, median = 0, p90 = 0;
};
CellTightnessStats cell_tightness_stats(const std::vector<CellTightness>& cells);

/// The cells as CSV: cell,pvs,seen,tightness per line, in the order they were drawn; the
/// tightness is empty for a cell that saw nothing.
std::string cell_tightness_csv(const std::vector<CellTightness>& cells);

struct ValidationReport {
  /// Viewpoints checked for misses: the random ones and those of the tightness cells.
  std::size_t viewpoints = 0;
  std::size_t rays = 0;  ///< segments cast (a target seen costs five with a crack > 0)
  std::vector<Miss> misses;
  std::size_t pvs_total = 0;   ///< summed |PVS| over the tightness viewpoints
  std::size_t seen_total = 0;  ///< summed number of objects seen from them
  double tightness() const { return seen_total ? double(pvs_total) / double(seen_total) : 0; }
  /// The per-cell tightness, in the order the cells were drawn
  /// (ValidationOptions::tightness_cells).
  std::vector<CellTightness> cells;
};

/// What one tightness viewpoint found: its cell's PVS and, per object, whether it was seen.
/// Valid only during the call of the observer.
struct TightnessViewpoint {
  std::uint32_t cell = 0;
  Vec3 viewpoint;
  std::span<const std::uint32_t> pvs;  ///< the cell's PVS as the file gives it
  std::span<const char> seen;          ///< seen[o] != 0: object o was seen from the viewpoint
};
/// Called for each tightness viewpoint, in order (urbanpvs-explain takes the excess from it).
using TightnessObserver = std::function<void(const TightnessViewpoint&)>;

/// The points of an object that the validator aims at: spread over its surfaces, no two
/// neighbours farther apart than `spacing`, when it blocks; over its box when it does not (it
/// may be as large as its box). Points shared by neighbouring surfaces are kept once.
std::vector<Vec3> target_points(const geometry::CityObject& o, double spacing);

/// Whether target q of `object` is seen from v through an opening at least `crack` (m) wide:
/// the segment v→q and four parallel ones crack/2 to its sides (horizontally and vertically,
/// across it) all reach it (RayScene::reaches). Why this closes cracks and hides no wider view:
/// see Validator.cpp. Adds the segments cast to *rays when given.
bool target_seen(const RayScene& scene, const Vec3& v, const Vec3& q, std::uint32_t object,
                 double crack, std::size_t* rays = nullptr);

/// The first of `targets` (of `object`) that target_seen finds seen from v, or nullptr.
const Vec3* first_target_seen(const RayScene& scene, const Vec3& v,
                              const std::vector<Vec3>& targets, std::uint32_t object, double crack,
                              std::size_t* rays = nullptr);

/// The lowest viewpoint of a cell over `at`: the bottom of its prism, or `eye_min` above the
/// scene's terrain there where that is higher, never above the prism's top. On a slope the
/// prism reaches from the cell's lowest ground: what lies below the terrain at `at` is earth,
/// where no one stands and from where a segment to a point also under the terrain crosses no
/// surface.
double lowest_viewpoint(const runtime::CellGeometry& c, const RayScene& scene, double eye_min,
                        Vec2 at);

/// A random viewpoint of a cell, as the validator draws them: uniform over the triangle, on the
/// top face when `top`, otherwise at a uniform height from lowest_viewpoint to the top.
Vec3 random_viewpoint(const runtime::CellGeometry& c, bool top, const RayScene& scene,
                      double eye_min, std::mt19937_64& rng);

/// Throws std::runtime_error when the file does not belong to the city (object count or ids
/// differ), std::invalid_argument for options out of their limits. `city` must be read with
/// the same options as for the bake.
ValidationReport validate(const geometry::City& city, const runtime::PvsFile& pvs,
                          const ValidationOptions& options, const TightnessObserver& observer = {});

}  // namespace urbanpvs::validate
