// SPDX-License-Identifier: GPL-3.0-or-later
// The ground truth of urbanpvs-validate: the input's own surfaces (CityObject::surfaces), traced
// by segments. It uses neither the occluders the readers derive from those surfaces nor the
// cull-map code, so a mistake in either (an occluder too tall, too wide, standing where the
// building floats) cannot hide itself here.
//  - Blockers are the surface polygons of every object that occludes (CityObject::occludes and
//    surfaces given), as planar polygons with holes: a segment meets one where it crosses the
//    polygon's plane (Newell normal) at a point inside its rings, in the projection that drops
//    the normal's largest axis.
//  - The ground holds up every building: below the foot of each wall that stands on the ground
//    (within 1 m of it) hangs a skirt, the wall continued down into the earth. So a viewpoint
//    lower than a building's foot (Delft: bases float up to ~0.5 m above the ground
//    interpolated between buildings; the 3D BAG has walls starting 25 cm above a base slab)
//    does not look under it through the earth, while views under raised parts (feet higher up)
//    stay open. Skirts block every object's segments, their own building's too.
//  - The terrain (a CityJSON TINRelief, a DEM given with --terrain), where the city has one, is
//    the earth: its triangles block every segment, like the skirts. On it, a building stands on
//    the ground when its lowest point is within 1 m of the highest terrain under it (its walls'
//    feet there get skirts); the median of its neighbours' bases, which judges flat cities,
//    says nothing on a slope.
//  - Objects that do not occlude (geometry beyond repair, unknown height) block nothing and are
//    as large as they may be: their whole box is theirs.
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "urbanpvs/geometry/city/CityModel.hpp"

namespace urbanpvs::validate {

using geometry::Box2;
using geometry::Box3;
using geometry::Vec2;
using geometry::Vec3;

/// Points spread over one planar surface: every vertex, points along every ring edge and a
/// lattice over the inside (holes left out), no two neighbours farther apart than `spacing`
/// (m, > 0). A surface of no area gives its vertices.
std::vector<Vec3> surface_points(const geometry::Surface3& surface, double spacing);

/// The same over the six faces of a box.
std::vector<Vec3> box_points(const Box3& box, double spacing);

/// Queries keep scratch state (visit stamps, the last blocker): one RayScene per thread.
class RayScene {
 public:
  explicit RayScene(const geometry::City& city);

  /// Whether the object's surfaces are blockers; otherwise it is its box, blocking nothing.
  static bool blocks(const geometry::CityObject& object) {
    return object.occludes && !object.surfaces.empty();
  }

  /// [m] Hits of another object this close before the end of a segment, or before the point
  /// where it meets its own object, do not stop it: walls shared by two buildings are two
  /// coincident polygons, one of each.
  static constexpr double kCoincident = 1e-3;

  /// True when the segment p→q (q a point of `object`, or near one) reaches `object` or q
  /// before any blocker: no surface of another object and no skirt (the earth) lies on it up
  /// to kCoincident before q, or up to where it first meets `object` itself.
  bool reaches(const Vec3& p, const Vec3& q, std::uint32_t object) const;

  /// Every object the segment p→q meets before any blocker stops it, with the parameter in
  /// [0, 1] where it meets it: the object of the first surface it meets (none when that is a
  /// skirt), and the objects without blockers whose box it enters before that.
  void first_met(const Vec3& p, const Vec3& q,
                 std::vector<std::pair<std::uint32_t, double>>& met) const;

  const Box2& bounds() const { return bounds_; }

  /// The highest terrain over p (its TIN triangles that hold p), or -infinity where the city
  /// has no terrain there. A viewpoint below it is inside the earth: it sees nothing.
  double ground_at(Vec2 p) const;

 private:
  static constexpr double kNone = 2;  ///< "no hit": beyond every segment parameter
  /// One blocker polygon, its rings projected to the plane that drops axis `drop`.
  struct Face {
    Vec3 normal;    // unit
    double offset;  // normal · x on the plane
    int drop;
    std::uint32_t first_ring, end_ring;  // into ring_start_
    Vec3 lo, hi;                         // bounding box
    std::uint32_t object;
    bool blocks = true;  // false: a surface the building may reach, a target only
  };
  struct TargetBox {
    Box3 box;
    std::uint32_t object;
  };
  enum Kind : std::uint32_t { kFace = 0, kSkirt = 1u << 30, kBox = 2u << 30 };
  static constexpr std::uint32_t kKindMask = 3u << 30;

  struct Segment {
    Vec3 p, d;    // p + t·d for t in [0, 1]
    Vec3 lo, hi;  // bounding box of the part for t in [0, t_max]
    Segment(const Vec3& from, const Vec3& to, double t_max);
  };

  /// Makes `face` the blocker polygon of the rings; false when they have no area.
  bool make_face(const std::vector<std::vector<Vec3>>& rings, std::uint32_t object, Face& face);
  /// Adds the city's terrain triangles as skirts (the earth); returns the highest terrain under
  /// each object's extent (-infinity where there is none).
  std::vector<double> add_terrain(const geometry::City& city, const std::vector<Box3>& extent);
  void add_face(const std::vector<std::vector<Vec3>>& rings, std::uint32_t object, bool blocks);
  /// Skirts below the bottom edges of a wall polygon whose foot is at most `highest_foot`,
  /// reaching down to `deep`.
  void add_skirts(const std::vector<Vec3>& wall, const Vec3& normal, double highest_foot,
                  double deep, std::uint32_t object);
  bool inside_rings(std::uint32_t first_ring, std::uint32_t end_ring, Vec2 p) const;
  /// Parameter in (0, t_max) where the segment meets the face, else kNone.
  double face_hit(const Face& f, const Segment& s, double t_max) const;
  static double box_entry(const Box3& box, const Segment& s, double t_max);
  /// Parameter in (0, t_max) where the segment first meets `object`'s own faces, else kNone.
  double own_hit(std::uint32_t object, const Segment& s, double t_max) const;
  /// Parameter in (0, t_max) where grid entry `entry`, a blocker of an object other than
  /// `object` (or the earth), meets the segment, else kNone.
  double blocker_hit(std::uint32_t entry, const Segment& s, std::uint32_t object,
                     double t_max) const;
  /// Parameter in (0, t_max) where some blocker of an object other than `object` (not
  /// necessarily the first) meets the segment, else kNone.
  double some_blocker_before(const Segment& s, std::uint32_t object, double t_max) const;
  /// Visits the grid entries along the segment's plan, each once, in the order of the cells
  /// the segment passes; stops when `visit` returns true or the next cell starts beyond
  /// *horizon (which `visit` may lower).
  template <class F>
  void walk(const Segment& s, const double* horizon, F&& visit) const;

  std::vector<Face> faces_;                  // grouped by object
  std::vector<std::uint32_t> object_faces_;  // object o's faces: [object_faces_[o], [o + 1])
  std::vector<Face> skirts_;
  std::vector<TargetBox> boxes_;
  std::vector<std::int32_t> box_of_;       // object → its index in boxes_, or -1 when it blocks
  std::vector<std::uint32_t> ring_start_;  // ring r: ring_vertex_[ring_start_[r] .. [r + 1])
  std::vector<Vec2> ring_vertex_;
  Box2 bounds_;
  double cell_ = 8;  // [m] side of a grid cell
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::uint32_t>> grid_;  // Kind | index
  // The terrain's triangles, bucketed by a grid of kGroundReach over their extent.
  std::vector<geometry::Triangle3> terrain_;
  Box2 terrain_bounds_;
  int terrain_nx_ = 0, terrain_ny_ = 0;
  std::vector<std::vector<std::uint32_t>> terrain_grid_;
  mutable std::vector<std::uint32_t> face_stamp_, skirt_stamp_, box_stamp_;
  mutable std::uint32_t query_ = 0;
  static constexpr std::uint32_t kNoBlocker = ~0u;
  mutable std::uint32_t last_blocker_ = kNoBlocker;  // the grid entry that blocked last
};

}  // namespace urbanpvs::validate
