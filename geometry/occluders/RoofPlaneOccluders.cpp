// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/occluders/RoofPlaneOccluders.hpp"

#include <algorithm>
#include <cmath>

#include "BoundarySimplification.hpp"
#include "urbanpvs/geometry/ParallelFor.hpp"
#include "urbanpvs/geometry/city/ConvexClip.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonOffset.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace urbanpvs::geometry {
namespace {

/// A face's plane lowered by ε times its slope, and the ground near the face.
struct LoweredFace {
  const RoofPrism* prism = nullptr;
  double drop = 0;            ///< ε times the plane's steepest slope
  std::vector<Polygon> near;  ///< a mitred offset of the prism's ground by ε: holds its ε-disks
  Box2 box;                   ///< of `near`

  double at(Vec2 p) const { return prism->top_at(p) - drop; }
};

/// The part of `box` where face `a`'s lowered plane lies above `b`'s: a half-plane (their
/// difference is linear) clipped to the box; all of it or none when the planes are parallel.
Polygon where_higher(const LoweredFace& a, const LoweredFace& b, const Box2& box) {
  auto excess = [&](Vec2 p) { return a.at(p) - b.at(p); };
  Ring out;
  // Kept where the excess is positive; the cut interpolates along the edge.
  clip_convex(box.corners(), out, excess,
              [](Vec2 p, Vec2 q, double sp, double sq) { return p + (sp / (sp - sq)) * (q - p); });
  // A corner on the line is kept and met again as the cut of the edge into it: a repeated
  // point, which CGAL's polygon set operations crash on. The hips of a hipped roof modelled from
  // OSM tags (RoofShapes.hpp) run exactly through such corners.
  Ring ring;
  for (Vec2 p : out)
    if (ring.empty() || p != ring.back()) ring.push_back(p);
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) return {};
  return {std::move(ring), {}};
}

void shrink_block_roofs(const std::vector<const RoofPrism*>& prisms, double epsilon,
                        const BlockOptions& options, std::vector<Occluder>& out) {
  // U ⊖ ε, made as the blocks' levels are (Blocks.hpp, BlockLevel::region): each face's ground
  // grown by half the gap tolerance, so that the slivers between faces whose plans do not meet
  // bit for bit close, the union simplified within the outline tolerance (near-collinear
  // vertices where the plans meet make the straight skeleton fall back to exact arithmetic at
  // every event), and the whole eroded by ε and as much more as it grew.
  const double grown = 0.5 * options.gap_tolerance;
  const double tolerance = options.outline_tolerance;
  std::vector<Polygon> ground;
  for (const RoofPrism* p : prisms) {
    if (grown > 0) {
      for (Polygon& g : grow_polygon(p->footprint, grown)) ground.push_back(std::move(g));
    } else {
      ground.push_back(p->footprint);
    }
  }
  std::vector<Polygon> eroded;
  for (const Polygon& u : detail::simplify_boundaries(union_polygons(ground), tolerance))
    for (Polygon& piece : shrink_polygon(u, epsilon + grown + tolerance))
      eroded.push_back(std::move(piece));
  if (eroded.empty()) return;
  Box2 all;
  for (const Polygon& p : eroded) all.extend(bounds(p));

  std::vector<LoweredFace> faces;
  for (const RoofPrism* p : prisms) {
    LoweredFace f;
    f.prism = p;
    f.drop = epsilon * std::hypot(p->slope.x, p->slope.y);
    // Simplified, the ground may lose up to the tolerance; a sliver closed above stands for
    // the face within half the gap: grown by as much more, `near` holds every disk of radius
    // ε around the ground and its slivers.
    for (const Polygon& simple : detail::simplify_boundaries({p->footprint}, tolerance))
      for (Polygon& g : grow_polygon(simple, epsilon + grown + tolerance))
        f.near.push_back(std::move(g));
    for (const Polygon& n : f.near) f.box.extend(bounds(n));
    faces.push_back(std::move(f));
  }
  for (const LoweredFace& f : faces) {
    if (!f.box.overlaps(all)) continue;
    std::vector<Polygon> region = intersect_polygons(f.near, eroded);
    if (region.empty()) continue;
    Box2 box;
    for (const Polygon& r : region) box.extend(bounds(r));
    std::vector<Polygon> lower;  // where another face within ε lies lower
    for (const LoweredFace& g : faces) {
      if (&g == &f || !g.box.overlaps(box)) continue;
      const Polygon higher = where_higher(f, g, box.grown(1));
      if (higher.outer.empty()) continue;
      if (!polygon_defect(higher).empty()) {  // a cut not to be trusted: g may lie lower anywhere
        lower.insert(lower.end(), g.near.begin(), g.near.end());
        continue;
      }
      for (Polygon& cut : intersect_polygons(g.near, {higher})) lower.push_back(std::move(cut));
    }
    if (!lower.empty()) region = subtract_polygons(region, lower);
    for (Polygon& piece : region) {
      // As the blocks' levels: a piece that touches itself would crash what comes next.
      if (!polygon_defect(piece).empty()) continue;
      Occluder o;
      o.block = kRoofPlaneBlock;
      o.top_z = f.prism->z0 - f.drop;
      o.slope = f.prism->slope;
      o.origin = f.prism->origin;
      o.bounds = bounds(piece);
      o.shape = std::move(piece);
      // Nothing of it above the ground: it hides nothing.
      if (o.top_high() > f.prism->ground_z) out.push_back(std::move(o));
    }
  }
}

}  // namespace

std::vector<Occluder> roof_plane_occluders(const std::vector<CityObject>& objects,
                                           const std::vector<Block>& blocks, double epsilon,
                                           const BlockOptions& options, unsigned threads) {
  // Blocks are independent: each one's occluders go to its own list and the lists are joined
  // in block order, so the result does not depend on the threads. CGAL's exact kernel is safe
  // across threads for objects that are not shared.
  std::vector<std::vector<Occluder>> per_block(blocks.size());
  parallel_for(blocks.size(), std::max(threads, 1u), [&](unsigned, std::size_t b) {
    std::vector<const RoofPrism*> prisms;
    for (std::uint32_t index : blocks[b].objects)
      if (objects[index].occludes)
        for (const RoofPrism& p : objects[index].roof_prisms) prisms.push_back(&p);
    if (!prisms.empty()) shrink_block_roofs(prisms, epsilon, options, per_block[b]);
  });
  std::vector<Occluder> out;
  for (std::vector<Occluder>& list : per_block)
    for (Occluder& o : list) out.push_back(std::move(o));
  return out;
}

}  // namespace urbanpvs::geometry
