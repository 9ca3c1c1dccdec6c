// Streets as a grid that is straight in some districts and irregular in others.
//
// Block corners sit on a rectilinear grid with varying spacing (50-74 m: ~2,000 blocks on 8 km²
// like Wonka's Vienna model). A coarse lattice of random displacements, bilinearly interpolated,
// bends the grid lines gently; how strongly varies by district, so some quarters stay almost
// straight (long views down streets) while others get irregular, non-axis-aligned quadrilateral
// blocks. Each grid line is one street with its own width, so lots are the grid cells inset by
// half the width of each bounding street.
#include "StreetNetwork.hpp"

#include <algorithm>
#include <cstddef>

#include "Geometry2d.hpp"
#include "urbanpvs/cities/Random.hpp"

namespace urbanpvs::cities::detail {
namespace {

constexpr std::uint64_t kStreamGrid = 1;
constexpr std::uint64_t kStreamWarp = 2;
constexpr std::uint64_t kStreamRiver = 3;

constexpr double kMinPitch = 50.0;  // grid spacing, metres (street centre to street centre)
constexpr double kMaxPitch = 74.0;
constexpr double kWarpSpacing = 400.0;   // a "district" of the irregularity field
constexpr double kWarpAmplitude = 40.0;  // largest displacement of a district node, metres
constexpr double kJitter = 7.0;          // largest per-corner displacement, metres
constexpr double kMinLotArea = 300.0;    // smaller leftovers become street space

// Street widths 8-25 m: mostly side streets, some avenues.
double streetWidth(Random& rng) {
  const double u = rng.uniform01();
  if (u < 0.65) return rng.uniform(8.0, 13.0);
  if (u < 0.90) return rng.uniform(13.0, 19.0);
  return rng.uniform(19.0, 25.0);
}

// Grid line positions covering [-pitch, side + pitch] so that edge blocks are cut by the city
// boundary rather than missing.
std::vector<double> gridLines(double side, Random& rng) {
  std::vector<double> lines;
  double pos = -rng.uniform(20.0, kMaxPitch);
  while (true) {
    lines.push_back(pos);
    if (pos > side) break;
    pos += rng.uniform(kMinPitch, kMaxPitch);
  }
  return lines;
}

// A smooth displacement field: random vectors on a coarse lattice, bilinearly interpolated, and
// a per-node irregularity in [0, 1] (squared uniform: most districts are fairly regular).
class WarpField {
 public:
  WarpField(double side, std::uint64_t seed) {
    n_ = static_cast<std::size_t>(side / kWarpSpacing) + 4;
    Random rng = Random::forStream(seed, kStreamWarp);
    nodes_.resize(n_ * n_);
    for (Node& node : nodes_) {
      const double u = rng.uniform01();
      node.irregularity = u * u;
      node.offset = Vec2{rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0)} *
                    (kWarpAmplitude * node.irregularity);
    }
  }

  struct Sample {
    Vec2 offset;
    double irregularity;
  };

  Sample at(Vec2 p) const {
    // Lattice origin at (-2 spacings) so that the grid's margin is covered.
    const double gx = p.x / kWarpSpacing + 2.0;
    const double gy = p.y / kWarpSpacing + 2.0;
    const double fx = std::clamp(std::floor(gx), 0.0, static_cast<double>(n_ - 2));
    const double fy = std::clamp(std::floor(gy), 0.0, static_cast<double>(n_ - 2));
    const auto ix = static_cast<std::size_t>(fx);
    const auto iy = static_cast<std::size_t>(fy);
    const double tx = std::clamp(gx - fx, 0.0, 1.0);
    const double ty = std::clamp(gy - fy, 0.0, 1.0);
    const Node& a = nodes_[iy * n_ + ix];
    const Node& b = nodes_[iy * n_ + ix + 1];
    const Node& c = nodes_[(iy + 1) * n_ + ix];
    const Node& d = nodes_[(iy + 1) * n_ + ix + 1];
    const double wa = (1.0 - tx) * (1.0 - ty);
    const double wb = tx * (1.0 - ty);
    const double wc = (1.0 - tx) * ty;
    const double wd = tx * ty;
    return {a.offset * wa + b.offset * wb + c.offset * wc + d.offset * wd,
            a.irregularity * wa + b.irregularity * wb + c.irregularity * wc + d.irregularity * wd};
  }

 private:
  struct Node {
    Vec2 offset;
    double irregularity = 0.0;
  };
  std::size_t n_ = 0;
  std::vector<Node> nodes_;
};

// The river: a straight band through the middle third of the city, mostly east-west or mostly
// north-south, never exactly axis-aligned (a direction from a random slope, no trigonometry).
struct River {
  Vec2 point;
  Vec2 normal;  // unit, perpendicular to the flow
  double water_width;
  double open_width;
};

River chooseRiver(double side, std::uint64_t seed) {
  Random rng = Random::forStream(seed, kStreamRiver);
  const Vec2 point = snapMm(Vec2{side * rng.uniform(0.35, 0.65), side * rng.uniform(0.35, 0.65)});
  const double slope = rng.uniform(-0.45, 0.45);
  const Vec2 flow = rng.chance(0.5) ? normalized(Vec2{1.0, slope}) : normalized(Vec2{slope, 1.0});
  const double water = snapMm(rng.uniform(40.0, 80.0));
  const double quays =
      snapMm(rng.uniform(8.0, 14.0) + rng.uniform(8.0, 14.0));  // a street each bank
  return {point, leftNormal(flow), water, water + quays};
}

// Where the river's centre line crosses the boundary of the square [0, side]².
OpenStrip riverStrip(const River& river, double side) {
  const Vec2 flow{river.normal.y, -river.normal.x};
  // Parametric range of the line inside the square (slab clipping).
  double t0 = -1e300;
  double t1 = 1e300;
  const double origin[2] = {river.point.x, river.point.y};
  const double dir[2] = {flow.x, flow.y};
  for (int axis = 0; axis < 2; ++axis) {
    if (dir[axis] == 0.0) continue;
    double a = (0.0 - origin[axis]) / dir[axis];
    double b = (side - origin[axis]) / dir[axis];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return {snapMm(river.point + flow * t0), snapMm(river.point + flow * t1), river.water_width,
          river.open_width};
}

// Clips a lot to the city square and removes the river band; may yield 0, 1 or 2 pieces.
std::vector<Ring> clipLot(const Ring& lot, double side, const River& river) {
  Ring r = lot;
  r = clipHalfPlane(r, {1.0, 0.0}, 0.0);
  r = clipHalfPlane(r, {-1.0, 0.0}, -side);
  r = clipHalfPlane(r, {0.0, 1.0}, 0.0);
  r = clipHalfPlane(r, {0.0, -1.0}, -side);
  std::vector<Ring> pieces;
  if (r.size() < 3) return pieces;
  // 2 mm more than half the band, so that snapping the lot to millimetres cannot move a building
  // line into the open band.
  const double half = river.open_width * 0.5 + 0.002;
  const double c = dot(river.normal, river.point);
  for (const double sign : {1.0, -1.0}) {
    Ring side_piece = clipHalfPlane(r, river.normal * sign, sign * c + half);
    if (side_piece.size() >= 3) pieces.push_back(std::move(side_piece));
  }
  return pieces;
}

// Makes a clipped lot well-shaped and exact: drops slivers and near-straight corners, snaps to
// millimetres, and rejects what is too small to build on.
std::optional<Ring> finishLot(const Ring& piece) {
  Ring r = simplifyConvex(piece, 3.0, 0.2);
  if (r.size() < 3) return std::nullopt;
  r = snapMm(r);
  if (!isStrictlyConvex(r) || signedArea(r) < kMinLotArea) return std::nullopt;
  // Too thin to hold a building row (e.g. a corner cut by the river at a shallow angle).
  if (insideDistance(r, centroid(r)) < 6.0) return std::nullopt;
  return r;
}

}  // namespace

StreetNetwork layoutStreets(double side, std::uint64_t seed) {
  Random rng = Random::forStream(seed, kStreamGrid);
  const std::vector<double> xs = gridLines(side, rng);
  const std::vector<double> ys = gridLines(side, rng);
  std::vector<double> col_width(xs.size());
  std::vector<double> row_width(ys.size());
  for (double& w : col_width) w = streetWidth(rng);
  for (double& w : row_width) w = streetWidth(rng);

  const WarpField warp(side, seed);
  const std::size_t nx = xs.size();
  const std::size_t ny = ys.size();
  std::vector<Vec2> corners(nx * ny);
  for (std::size_t j = 0; j < ny; ++j) {
    for (std::size_t i = 0; i < nx; ++i) {
      const Vec2 p{xs[i], ys[j]};
      const WarpField::Sample s = warp.at(p);
      const double jitter = kJitter * (0.25 + 0.75 * s.irregularity);
      corners[j * nx + i] =
          p + s.offset + Vec2{rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter)};
    }
  }

  const River river = chooseRiver(side, seed);
  StreetNetwork net;
  net.river = riverStrip(river, side);
  for (std::size_t j = 0; j + 1 < ny; ++j) {
    for (std::size_t i = 0; i + 1 < nx; ++i) {
      // Counter-clockwise: bottom edge on row j, right on column i+1, top on row j+1, left on i.
      const Ring cell{corners[j * nx + i], corners[j * nx + i + 1], corners[(j + 1) * nx + i + 1],
                      corners[(j + 1) * nx + i]};
      const std::vector<double> half_widths{row_width[j] * 0.5, col_width[i + 1] * 0.5,
                                            row_width[j + 1] * 0.5, col_width[i] * 0.5};
      const std::optional<Ring> lot = insetConvex(cell, half_widths, 10.0);
      if (!lot) continue;
      for (const Ring& piece : clipLot(*lot, side, river)) {
        if (std::optional<Ring> finished = finishLot(piece))
          net.lots.push_back(std::move(*finished));
      }
    }
  }
  return net;
}

}  // namespace urbanpvs::cities::detail
