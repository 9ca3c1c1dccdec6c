// SPDX-License-Identifier: MIT
// The cells section of version 2.x (FORMAT.md, "cells, version 2"): the view cells as an indexed
// triangle mesh. Neighbouring cells share their corners, so a vertex is stored once for about two
// cells; coordinates are integers of a fixed unit (millimetres), delta-coded in the order the
// cells first use them; a corner is "the next new vertex" (one byte) or a short step back; z
// ranges are deltas from the previous cell. Neighbours are not stored: two cells are neighbours
// when they share an edge's two vertices, which the reader derives. About 8 bytes per cell
// against 76 for the float64 records of 1.x (runtime/README.md, measurements).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <unordered_map>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 24;  // cells u32, vertices u32, unit f64, grid density f64
/// Stored integers stay within ±2^30 units (±1,073 km at 1 mm), so a delta between two of them
/// fits a zigzag-coded 32-bit varint and unit × value is exact enough in float64.
constexpr std::int64_t kLimit = std::int64_t{1} << 30;
constexpr double kMinUnit = 1e-9;
constexpr double kMaxUnit = 1e3;
constexpr double kMaxGridDensity = 64;

std::uint32_t zigzag(std::int64_t d) noexcept {
  const auto v = static_cast<std::int32_t>(d);  // |d| <= 2^31 - 1 by kLimit
  return (static_cast<std::uint32_t>(v) << 1) ^ static_cast<std::uint32_t>(v >> 31);
}

std::int64_t unzigzag(std::uint32_t z) noexcept {
  return static_cast<std::int64_t>(z >> 1) ^ -static_cast<std::int64_t>(z & 1u);
}

/// value / unit rounded as asked, checked against kLimit.
std::int64_t quantize(double value, double unit, double (*round)(double), std::size_t cell) {
  const double q = round(value / unit);
  if (!(std::fabs(q) <= static_cast<double>(kLimit))) {
    throw PvsWriteError("cell " + std::to_string(cell) + ": coordinate " + std::to_string(value) +
                        " m is more than 2^30 units (" + std::to_string(unit) +
                        " m) from the local origin");
  }
  return static_cast<std::int64_t>(q);
}

double nearest(double v) {
  return std::nearbyint(v);
}

using IntPoint = std::array<std::int64_t, 2>;

/// Sign of the turn a -> b -> c, exact: coordinates are within ±2^30, so each product fits in
/// 63 bits, and comparing the two avoids the subtraction that could overflow.
int orientation(const IntPoint& a, const IntPoint& b, const IntPoint& c) noexcept {
  const std::int64_t l = (b[0] - a[0]) * (c[1] - a[1]);
  const std::int64_t r = (b[1] - a[1]) * (c[0] - a[0]);
  return (l > r) - (l < r);
}

/// Neighbour k of cell c is the lowest-index other cell that has both vertices of c's edge k
/// and its third vertex strictly on the other side of that edge (FORMAT.md): stacked twins and
/// degenerate cells are not across the edge. Every edge of a cell with three distinct corners
/// is listed once, at the lower of its two vertices, with its upper vertex, its cell, its
/// number in the cell, and the side of that edge, taken from lower to upper, on which the
/// cell's third vertex lies; lists are in ascending cell order. Two entries of a list with the
/// same upper vertex and opposite sides are then across one edge from each other, and each
/// entry takes the first such one: the lowest-index cell (a cell is in a group at most once). The
/// side is the sign of the cell's orientation, flipped where the cell runs the edge from upper to
/// lower: the orientation of a triangle's corners is the same from each of them (exact integer
/// determinants), so no vertex is read twice. A list holds about four entries in a real mesh:
/// pairing them within it reads one run of memory, where scanning each cell of a vertex and reading
/// its corners and third vertex elsewhere was a fifth of a 2.x file's load time in `perf`.
void derive_neighbours(const std::vector<std::array<std::uint32_t, 3>>& corners,
                       const std::vector<IntPoint>& points, CellTable& out) {
  struct EdgeEntry {
    std::uint32_t upper, cell;
    std::int32_t side;  ///< of the cell's third vertex, seen along lower -> upper (0: none)
    std::uint32_t k;    ///< the edge's number in its cell
  };
  const auto distinct = [](const std::array<std::uint32_t, 3>& t) {
    return t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
  };
  std::vector<std::uint32_t> start(points.size() + 1, 0);
  for (const auto& t : corners) {
    if (!distinct(t)) continue;
    for (std::size_t k = 0; k < 3; ++k) ++start[std::min(t[k], t[(k + 1) % 3]) + 1];
  }
  for (std::size_t v = 0; v + 1 < start.size(); ++v) start[v + 1] += start[v];
  std::vector<EdgeEntry> edges(start.back());
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t c = 0; c < corners.size(); ++c) {
    const auto& t = corners[c];
    if (!distinct(t)) continue;
    const int turn = orientation(points[t[0]], points[t[1]], points[t[2]]);
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t a = t[k], b = t[(k + 1) % 3];
      edges[fill[std::min(a, b)]++] = {std::max(a, b), c, a < b ? turn : -turn, k};
    }
  }
  // A cell with two equal corners has no side along any edge and no neighbours; its edges are
  // in no list, so nothing takes it as one either. Sorted by upper vertex (then cell), each
  // list falls into groups of the cells that share one edge; in a group, an entry's neighbour
  // is the first entry of the opposite side. Linear in a group and O(L log L) in a list, so a
  // hostile file of one hub vertex or of many stacked cells costs no quadratic time.
  out.neighbours.assign(corners.size(), {kNoCell, kNoCell, kNoCell});
  for (std::size_t v = 0; v + 1 < start.size(); ++v) {
    EdgeEntry* const first = edges.data() + start[v];
    EdgeEntry* const last = edges.data() + start[v + 1];
    std::sort(first, last, [](const EdgeEntry& x, const EdgeEntry& y) {
      return x.upper != y.upper ? x.upper < y.upper : x.cell < y.cell;
    });
    for (EdgeEntry* group = first; group != last;) {
      EdgeEntry* end = group;
      const EdgeEntry* positive = nullptr;
      const EdgeEntry* negative = nullptr;
      for (; end != last && end->upper == group->upper; ++end) {
        if (end->side > 0 && positive == nullptr) positive = end;
        if (end->side < 0 && negative == nullptr) negative = end;
      }
      for (const EdgeEntry* e = group; e != end; ++e) {
        const EdgeEntry* across = e->side > 0 ? negative : e->side < 0 ? positive : nullptr;
        if (across != nullptr) out.neighbours[e->cell][e->k] = across->cell;
      }
      group = end;
    }
  }
}

}  // namespace

std::vector<unsigned char> write_cells_v2(const std::vector<CellRecord>& cells,
                                          const EncodeOptions& options) {
  const double unit = 0.001;
  const double density = options.grid_cells_per_cell;
  if (!(density > 0 && density <= kMaxGridDensity)) {
    throw PvsWriteError("grid_cells_per_cell must be in (0, 64]");
  }
  // Vertices by first use, deduplicated on their quantized position.
  std::unordered_map<std::uint64_t, std::uint32_t> index_of;
  std::vector<std::array<std::int64_t, 2>> vertices;
  ByteWriter corners, z;
  std::uint32_t next = 0;
  std::int64_t previous_z = 0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const CellRecord& c = cells[i];
    for (const Point2& p : c.triangle) {
      const std::int64_t qx = quantize(p.x, unit, nearest, i);
      const std::int64_t qy = quantize(p.y, unit, nearest, i);
      const std::uint64_t key =
          (static_cast<std::uint64_t>(qx) << 32) ^ (static_cast<std::uint64_t>(qy) & 0xFFFFFFFFu);
      const auto [it, inserted] = index_of.try_emplace(key, next);
      if (inserted) {
        vertices.push_back({qx, qy});
        corners.varint(0);
        ++next;
      } else {
        corners.varint(next - it->second);
      }
    }
    // Outwards: the stored prism contains the baked one.
    const std::int64_t lo = quantize(c.z_min, unit, std::floor, i);
    const std::int64_t hi = quantize(c.z_max, unit, std::ceil, i);
    z.varint(zigzag(lo - previous_z));
    z.varint(static_cast<std::uint32_t>(hi - lo));
    previous_z = lo;
  }
  ByteWriter w;
  w.u32(static_cast<std::uint32_t>(cells.size()));
  w.u32(static_cast<std::uint32_t>(vertices.size()));
  w.f64(unit);
  w.f64(density);
  std::array<std::int64_t, 2> previous{0, 0};
  for (const auto& v : vertices) {
    w.varint(zigzag(v[0] - previous[0]));
    w.varint(zigzag(v[1] - previous[1]));
    previous = v;
  }
  w.raw(corners.bytes().data(), corners.bytes().size());
  w.raw(z.bytes().data(), z.bytes().size());
  return std::move(w.bytes());
}

bool read_cells_v2(const SectionBytesView& in, CellTable& out, const char*& detail) {
  if (in.size < kHeaderSize) {
    detail = "cells: section shorter than its header";
    return false;
  }
  out.count = load_u32(in.data);
  const std::uint32_t vertex_count = load_u32(in.data + 4);
  const double unit = load_f64(in.data + 8);
  out.grid_density = load_f64(in.data + 16);
  const std::size_t body = in.size - kHeaderSize;
  // Every cell takes at least 5 bytes (3 corners, 2 z varints), every vertex 2; every vertex is
  // introduced by a corner. These bound the allocations below by the section length.
  if (out.count == kNoCell || out.count > body / 5 || vertex_count > body / 2 ||
      vertex_count > std::uint64_t{3} * out.count) {
    detail = "cells: counts do not fit the section length";
    return false;
  }
  if (!(unit >= kMinUnit && unit <= kMaxUnit)) {
    detail = "cells: unit not in [1e-9, 1000] m";
    return false;
  }
  if (!(out.grid_density > 0 && out.grid_density <= kMaxGridDensity)) {
    detail = "cells: grid density not in (0, 64]";
    return false;
  }
  const unsigned char* p = in.data + kHeaderSize;
  const unsigned char* const end = in.data + in.size;
  std::vector<Point2> vertices(vertex_count);
  std::vector<IntPoint> points(vertex_count);
  std::int64_t x = 0, y = 0;
  for (std::uint32_t i = 0; i < vertex_count; ++i) {
    std::uint32_t dx, dy;
    if (!read_varint(p, end, dx) || !read_varint(p, end, dy)) {
      detail = "cells: vertex list truncated";
      return false;
    }
    x += unzigzag(dx);
    y += unzigzag(dy);
    if (x < -kLimit || x > kLimit || y < -kLimit || y > kLimit) {
      detail = "cells: vertex beyond 2^30 units";
      return false;
    }
    points[i] = {x, y};
    vertices[i] = {static_cast<double>(x) * unit, static_cast<double>(y) * unit};
  }
  std::vector<std::array<std::uint32_t, 3>> corners(out.count);
  out.shapes.resize(out.count);
  std::uint32_t next = 0;
  for (std::uint32_t c = 0; c < out.count; ++c) {
    for (std::size_t k = 0; k < 3; ++k) {
      std::uint32_t back;
      if (!read_varint(p, end, back)) {
        detail = "cells: corner list truncated";
        return false;
      }
      if (back == 0 ? next >= vertex_count : back > next) {
        detail = "cells: corner refers to no vertex";
        return false;
      }
      const std::uint32_t v = back == 0 ? next++ : next - back;
      corners[c][k] = v;
      out.shapes[c].triangle[k] = vertices[v];
    }
  }
  if (next != vertex_count) {
    detail = "cells: a vertex is used by no cell";
    return false;
  }
  std::int64_t z = 0;
  for (CellShape& s : out.shapes) {
    std::uint32_t dz, height;
    if (!read_varint(p, end, dz) || !read_varint(p, end, height)) {
      detail = "cells: z ranges truncated";
      return false;
    }
    z += unzigzag(dz);
    if (z < -kLimit || z > kLimit || height > 2 * kLimit || z + height > kLimit) {
      detail = "cells: z range beyond 2^30 units";
      return false;
    }
    s.z_min = static_cast<double>(z) * unit;
    s.z_max = static_cast<double>(z + height) * unit;
  }
  if (p != end && !in.allow_extension) {
    detail = "cells: bytes after the last z range";
    return false;
  }
  derive_neighbours(corners, points, out);
  return true;
}

}  // namespace urbanpvs::runtime::detail
