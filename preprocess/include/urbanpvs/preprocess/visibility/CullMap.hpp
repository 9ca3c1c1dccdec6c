// SPDX-License-Identifier: GPL-3.0-or-later
// A cull map (thesis 4.3.2, 5.5): an orthographic top-down height map over the ground. Each pixel
// holds the height below which everything above that pixel is hidden (the umbra's height).
// Heights are floats like a depth buffer; every value is rounded *down* from the exact double
// so that a stored height is never above the true umbra (conservative).
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::preprocess {

using geometry::Box2;
using geometry::Vec2;

/// Pixel size and ε must satisfy ε >= k·√2/2 (thesis 7.2, corollary 5): then a shadow of an
/// ε-shrunk occluder that covers a pixel's centre covers the whole pixel for every viewpoint
/// within ε of the sample, so point-sampled rasterization stays conservative. OpenGL snaps
/// vertices to 1/256 of a pixel (llvmpipe's 8 subpixel bits), which can move a shadow's border
/// by k·√2/256; that slack is added: ε >= k·(√2/2 + 1/128).
struct CullMapSettings {
  double epsilon = 1.0;  ///< occluder shrinking and sample spacing [Units: m] [Limit: > 0]
  double pixel = 1.39;   ///< cull-map pixel size k [Units: m] [Limit: 0 < k <= max_pixel(ε)]

  /// Largest pixel size allowed for `epsilon`.
  static double max_pixel(double epsilon) { return epsilon / (std::sqrt(2.0) / 2 + 1.0 / 128); }
  /// Throws std::invalid_argument naming the value to change when the coupling is broken.
  void validate() const;
};

/// Where the map lies: `origin` is the lower-left corner of pixel (0, 0).
struct CullMapGrid {
  Vec2 origin;
  double pixel = 1;
  int width = 0;
  int height = 0;

  Vec2 center(int i, int j) const {
    return {origin.x + (i + 0.5) * pixel, origin.y + (j + 0.5) * pixel};
  }
  Box2 bounds() const { return {origin, {origin.x + width * pixel, origin.y + height * pixel}}; }

  /// Pixels [i0, i1] × [j0, j1] whose square meets `box` (floor on both ends: a box edge on a
  /// pixel border touches the pixel beyond too); may reach outside the grid.
  struct PixelRange {
    long long i0, j0, i1, j1;
  };
  PixelRange touched(const Box2& box) const {
    auto at = [&](double v, double o) {
      return static_cast<long long>(std::floor((v - o) / pixel));
    };
    return {at(box.min.x, origin.x), at(box.min.y, origin.y), at(box.max.x, origin.x),
            at(box.max.y, origin.y)};
  }
  /// The grid of pixel size `pixel` covering `area` (grown to whole pixels).
  static CullMapGrid covering(const Box2& area, double pixel);
};

class CullMap {
 public:
  /// Nothing is hidden anywhere yet: every pixel holds -infinity.
  explicit CullMap(const CullMapGrid& grid);

  const CullMapGrid& grid() const { return grid_; }
  float at(int i, int j) const { return z_[index(i, j)]; }
  float& at(int i, int j) { return z_[index(i, j)]; }
  const std::vector<float>& values() const { return z_; }
  std::vector<float>& values() { return z_; }

  /// Resets every pixel to `value`.
  void fill(float value);

  static constexpr float kNothingHidden = -std::numeric_limits<float>::infinity();

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(grid_.width) +
           static_cast<std::size_t>(i);
  }
  CullMapGrid grid_;
  std::vector<float> z_;
};

/// The largest float not above `z`: heights enter the map rounded towards -infinity.
inline float float_below(double z) {
  float f = static_cast<float>(z);
  if (static_cast<double>(f) > z) {
    // One float step down, without a libm call (this runs once per pixel written): for finite
    // non-zero floats the next lower value is one unit less in magnitude when positive, one more
    // when negative; below +0/-0 comes the smallest negative subnormal.
    std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
    if (f == 0.0f)
      bits = 0x80000001u;
    else if (f > 0.0f)
      --bits;
    else if (bits != 0xff800000u)  // -infinity has nothing below
      ++bits;
    f = std::bit_cast<float>(bits);
  }
  return f;
}

/// True when `box` lies entirely outside the interior of the map's area.
bool outside_map(const CullMapGrid& grid, const Box2& box);
/// True when `box` lies entirely inside the map's area.
bool inside_map(const CullMapGrid& grid, const Box2& box);

}  // namespace urbanpvs::preprocess
