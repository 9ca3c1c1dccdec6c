// SPDX-License-Identifier: MIT
// The cells section of version 1.x: one fixed 76-byte record per view cell (FORMAT.md, "cells,
// version 1"). Read into the same decoded table as version 2, so queries do not care which
// version a file has.
#include <cmath>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 8;  // count u32, reserved u32
constexpr std::size_t kRecordSize = format::kCellRecordSize;
static_assert(kRecordSize == 6 * 8 + 2 * 8 + 3 * 4, "triangle, z range, neighbours");

}  // namespace

std::vector<unsigned char> write_cells_v1(const std::vector<CellRecord>& cells) {
  ByteWriter w;
  w.u32(static_cast<std::uint32_t>(cells.size()));
  w.u32(0);
  for (const CellRecord& c : cells) {
    for (const Point2& p : c.triangle) {
      w.f64(p.x);
      w.f64(p.y);
    }
    w.f64(c.z_min);
    w.f64(c.z_max);
    for (std::uint32_t n : c.neighbours) w.u32(n);
  }
  return std::move(w.bytes());
}

bool read_cells_v1(const SectionBytesView& in, CellTable& out, const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint32_t reserved;
  std::uint64_t records_size;
  if (!r.u32(out.count) || !r.u32(reserved) || reserved != 0 ||
      !checked_mul(out.count, kRecordSize, records_size) || records_size > r.remaining() ||
      (records_size != r.remaining() && !in.allow_extension) || out.count == kNoCell) {
    detail = "cells: count does not match the section length";
    return false;
  }
  out.shapes.resize(out.count);
  out.neighbours.resize(out.count);
  out.grid_density = 1;  // unused: 1.x files store their grid
  for (std::uint32_t i = 0; i < out.count; ++i) {
    const unsigned char* rec = in.data + kHeaderSize + std::size_t{i} * kRecordSize;
    double v[8];
    for (int k = 0; k < 8; ++k) {
      v[k] = load_f64(rec + 8 * k);
      if (!std::isfinite(v[k])) {
        detail = "cells: non-finite coordinate";
        return false;
      }
    }
    if (!(v[6] <= v[7])) {
      detail = "cells: z_min above z_max";
      return false;
    }
    out.shapes[i] = {{Point2{v[0], v[1]}, Point2{v[2], v[3]}, Point2{v[4], v[5]}}, v[6], v[7]};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t n = load_u32(rec + 64 + 4 * k);
      if (n != kNoCell && n >= out.count) {
        detail = "cells: neighbour index out of range";
        return false;
      }
      out.neighbours[i][static_cast<std::size_t>(k)] = n;
    }
  }
  return true;
}

CellGeometry cell_at(const CellTable& table, std::uint32_t index) noexcept {
  CellGeometry c;
  const CellShape& s = table.shapes[index];
  c.triangle = s.triangle;
  c.z_min = s.z_min;
  c.z_max = s.z_max;
  c.neighbours = table.neighbours[index];
  return c;
}

}  // namespace urbanpvs::runtime::detail
