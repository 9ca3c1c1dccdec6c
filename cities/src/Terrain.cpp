#include "Terrain.hpp"

#include <algorithm>
#include <cmath>

#include "Geometry2d.hpp"
#include "urbanpvs/cities/Random.hpp"

namespace urbanpvs::cities::detail {
namespace {

constexpr double kSpacing = 20.0;        // metres between terrain nodes
constexpr double kTerrainMargin = 80.0;  // beyond the city square: the default cell margin is 50
constexpr std::uint64_t kTerrainStream = 0x7E44A1;

struct Bump {
  Vec2 centre;
  double radius2 = 0, amplitude = 0;
};

// (1 - t²)³ inside the bump: smooth, and only + - * / so that every platform rounds alike.
double height(const std::vector<Bump>& bumps, Vec2 p) {
  double h = 0;
  for (const Bump& b : bumps) {
    const double dx = p.x - b.centre.x, dy = p.y - b.centre.y;
    const double t2 = (dx * dx + dy * dy) / b.radius2;
    if (t2 < 1) {
      const double u = 1 - t2;
      h += b.amplitude * u * u * u;
    }
  }
  return h;
}

void raise(Solid& solid, double dz) {
  for (Vec3& v : solid.vertices) v.z = snapMm(v.z + dz);
}

}  // namespace

Terrain makeTerrain(double side, std::uint64_t seed, double hills) {
  Random rng = Random::forStream(seed, kTerrainStream);
  const double lo = -kTerrainMargin, hi = side + kTerrainMargin;
  std::vector<Bump> bumps(std::max<std::size_t>(4, static_cast<std::size_t>(side * side / 60000)));
  for (Bump& b : bumps) {
    b.centre = {rng.uniform(lo, hi), rng.uniform(lo, hi)};
    const double r = rng.uniform(120, 350);
    b.radius2 = r * r;
    b.amplitude = rng.uniform(-0.5, 1.0);
  }
  Terrain t;
  t.origin = {lo, lo};
  t.spacing = kSpacing;
  t.columns = t.rows = static_cast<int>(std::ceil((hi - lo) / kSpacing)) + 1;
  t.heights.resize(static_cast<std::size_t>(t.columns) * static_cast<std::size_t>(t.rows));
  for (int j = 0; j < t.rows; ++j)
    for (int i = 0; i < t.columns; ++i)
      t.heights[static_cast<std::size_t>(j) * t.columns + i] =
          height(bumps, {lo + i * kSpacing, lo + j * kSpacing});
  const auto [min, max] = std::minmax_element(t.heights.begin(), t.heights.end());
  const double base = *min, scale = *max > *min ? hills / (*max - *min) : 0.0;
  for (double& h : t.heights) h = snapMm((h - base) * scale);
  return t;
}

void standOnTerrain(City& city) {
  const Terrain& t = city.terrain;
  if (t.empty()) return;
  auto index = [&](double v, double origin, int n) {
    return std::clamp(static_cast<int>(std::floor((v - origin) / t.spacing)), 0, n - 1);
  };
  for (Building& b : city.buildings) {
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const Vec2& p : b.footprint.outer)
      x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x),
      y1 = std::max(y1, p.y);
    double ground = INFINITY;
    for (int j = index(y0, t.origin.y, t.rows); j <= index(y1, t.origin.y, t.rows) + 1; ++j)
      for (int i = index(x0, t.origin.x, t.columns); i <= index(x1, t.origin.x, t.columns) + 1; ++i)
        ground = std::min(ground, t.at(std::min(i, t.columns - 1), std::min(j, t.rows - 1)));
    b.ground_z = snapMm(ground);
    raise(b.solid, b.ground_z);
    for (BuildingPart& part : b.parts) raise(part.solid, b.ground_z);
  }
}

}  // namespace urbanpvs::cities::detail
