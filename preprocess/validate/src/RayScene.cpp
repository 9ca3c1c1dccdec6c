// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/validate/RayScene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "urbanpvs/geometry/PolygonOffset.hpp"

namespace urbanpvs::validate {

RayScene::RayScene(const geometry::City& city, double crack) {
  for (const geometry::CityObject& o : city.objects) {
    // A part that reaches the ground stands on solid ground: nothing is seen below its lowest
    // point (ground_z is only where the modeller put the base; in Delft bases float up to ~0.3 m
    // above the ground interpolated between buildings, and a viewpoint at the cells' bottom
    // would otherwise look under them, through the ground). Raised parts (passages, overhangs)
    // have no prism at all, so views under them stay open.
    // Grown by `crack`: buildings that share a wall are one solid. Without it a sight line
    // running along the shared wall enters neither prism and "sees" through a crack a few
    // millimetres wide (found in Delft, where rows of sheds share walls with a house).
    for (const geometry::OccluderPrism& p : o.occluders)
      for (Polygon& g : geometry::grow_polygon(p.footprint, crack)) {
        grown_.push_back(std::move(g));
        prisms_.push_back({&grown_.back(), geometry::bounds(grown_.back()), kBelowGround, p.top_z,
                           o.index, true});
      }
    for (const Polygon& f : o.footprint)
      prisms_.push_back({&f, geometry::bounds(f), o.bbox.zmin, o.bbox.zmax, o.index, false});
  }
  for (const Prism& p : prisms_) bounds_.extend(p.box);
  if (bounds_.empty()) bounds_ = {{0, 0}, {1, 1}};
  nx_ = std::max(1, static_cast<int>(std::ceil((bounds_.max.x - bounds_.min.x) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((bounds_.max.y - bounds_.min.y) / cell_)));
  grid_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  for (std::uint32_t i = 0; i < prisms_.size(); ++i) {
    const Box2& b = prisms_[i].box;
    const int x0 = std::clamp(static_cast<int>((b.min.x - bounds_.min.x) / cell_), 0, nx_ - 1);
    const int x1 = std::clamp(static_cast<int>((b.max.x - bounds_.min.x) / cell_), 0, nx_ - 1);
    const int y0 = std::clamp(static_cast<int>((b.min.y - bounds_.min.y) / cell_), 0, ny_ - 1);
    const int y1 = std::clamp(static_cast<int>((b.max.y - bounds_.min.y) / cell_), 0, ny_ - 1);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) grid_[static_cast<std::size_t>(y * nx_ + x)].push_back(i);
  }
  stamp_.assign(prisms_.size(), 0);
}

double RayScene::entry(const Prism& prism, const Point3& p, const Point3& q) {
  constexpr double kMiss = 2;
  const Vec2 a{p.x, p.y}, d{q.x - p.x, q.y - p.y};
  // Parameters where the segment crosses the footprint's boundary; between them it alternates
  // between outside and inside.
  std::vector<double> ts{0.0};
  geometry::for_each_edge(*prism.footprint, [&](Vec2 u, Vec2 v) {
    const Vec2 e = v - u;
    const double den = geometry::cross(d, e);
    if (den == 0) return;
    const double t = geometry::cross(u - a, e) / den;
    const double s = geometry::cross(u - a, d) / den;
    if (t > 0 && t < 1 && s >= 0 && s < 1) ts.push_back(t);
  });
  ts.push_back(1.0);
  std::sort(ts.begin(), ts.end());
  const double dz = q.z - p.z;
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    const double t0 = ts[i], t1 = ts[i + 1];
    if (t1 <= t0) continue;
    const double tm = 0.5 * (t0 + t1);
    if (!geometry::inside(*prism.footprint, a + tm * d)) continue;
    // Within [t0, t1] the segment is above the footprint; clip by the prism's z range.
    double lo = t0, hi = t1;
    if (dz == 0) {
      if (p.z < prism.zmin || p.z > prism.zmax) continue;
    } else {
      const double ta = (prism.zmin - p.z) / dz, tb = (prism.zmax - p.z) / dz;
      lo = std::max(lo, std::min(ta, tb));
      hi = std::min(hi, std::max(ta, tb));
    }
    if (lo < hi) return lo;
  }
  return kMiss;
}

// Visits every prism whose grid cells the segment's 2D projection passes (2D DDA), once each.
template <class F>
void RayScene::for_each_candidate(const Point3& p, const Point3& q, F&& f) const {
  ++query_;
  double x = (p.x - bounds_.min.x) / cell_, y = (p.y - bounds_.min.y) / cell_;
  const double ex = (q.x - bounds_.min.x) / cell_, ey = (q.y - bounds_.min.y) / cell_;
  const double dx = ex - x, dy = ey - y;
  int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
  const int stepx = dx > 0 ? 1 : -1, stepy = dy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  double tmx = dx != 0 ? ((dx > 0 ? ix + 1 - x : x - ix) / std::abs(dx)) : inf;
  double tmy = dy != 0 ? ((dy > 0 ? iy + 1 - y : y - iy) / std::abs(dy)) : inf;
  const double tdx = dx != 0 ? 1 / std::abs(dx) : inf, tdy = dy != 0 ? 1 / std::abs(dy) : inf;
  for (double t = 0; t <= 1;) {
    if (ix >= 0 && iy >= 0 && ix < nx_ && iy < ny_)
      for (std::uint32_t id : grid_[static_cast<std::size_t>(iy * nx_ + ix)])
        if (stamp_[id] != query_) {
          stamp_[id] = query_;
          if (f(prisms_[id])) return;
        }
    if (tmx < tmy)
      t = tmx, tmx += tdx, ix += stepx;
    else
      t = tmy, tmy += tdy, iy += stepy;
  }
}

bool RayScene::blocked(const Point3& p, const Point3& q, std::uint32_t skip) const {
  bool hit = false;
  for_each_candidate(p, q, [&](const Prism& pr) {
    if (!pr.blocker || pr.object == skip) return false;
    hit = entry(pr, p, q) < 1;
    return hit;
  });
  return hit;
}

void RayScene::seen_along(const Point3& p, const Point3& q,
                          std::vector<std::uint32_t>& seen) const {
  double first_block = 1;
  std::vector<std::pair<double, std::uint32_t>> targets;
  for_each_candidate(p, q, [&](const Prism& pr) {
    const double t = entry(pr, p, q);
    if (t >= 1) return false;
    if (pr.blocker)
      first_block = std::min(first_block, t);
    else
      targets.emplace_back(t, pr.object);
    return false;
  });
  for (auto [t, object] : targets)
    if (t <= first_block) seen.push_back(object);
}

}  // namespace urbanpvs::validate
