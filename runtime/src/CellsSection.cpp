// SPDX-License-Identifier: MIT
// The cells section: one fixed 76-byte record per view cell (FORMAT.md, "cells"). Triangles
// stay float64: they are what locate() tests points against, and rounding them would open
// cracks between neighbouring cells.
#include <cmath>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 8;  // count u32, reserved u32
constexpr std::size_t kRecordSize = format::kCellRecordSize;
static_assert(kRecordSize == 6 * 8 + 2 * 8 + 3 * 4, "triangle, z range, neighbours");

const unsigned char* record(const CellsView& view, std::uint32_t index) noexcept {
  return view.records + std::size_t{index} * kRecordSize;
}

}  // namespace

std::vector<unsigned char> write_cells(const std::vector<CellRecord>& cells) {
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

bool read_cells(const SectionBytesView& in, CellsView& out, const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint32_t reserved;
  std::uint64_t records_size;
  if (!r.u32(out.count) || !r.u32(reserved) || reserved != 0 ||
      !checked_mul(out.count, kRecordSize, records_size) || records_size > r.remaining() ||
      (records_size != r.remaining() && !in.allow_extension) || out.count == kNoCell) {
    detail = "cells: count does not match the section length";
    return false;
  }
  out.records = in.data + kHeaderSize;
  for (std::uint32_t i = 0; i < out.count; ++i) {
    const unsigned char* rec = record(out, i);
    for (int k = 0; k < 8; ++k) {
      if (!std::isfinite(load_f64(rec + 8 * k))) {
        detail = "cells: non-finite coordinate";
        return false;
      }
    }
    if (!(load_f64(rec + 48) <= load_f64(rec + 56))) {
      detail = "cells: z_min above z_max";
      return false;
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t n = load_u32(rec + 64 + 4 * k);
      if (n != kNoCell && n >= out.count) {
        detail = "cells: neighbour index out of range";
        return false;
      }
    }
  }
  return true;
}

std::array<Point2, 3> triangle_at(const CellsView& view, std::uint32_t index) noexcept {
  const unsigned char* rec = record(view, index);
  return {Point2{load_f64(rec), load_f64(rec + 8)}, Point2{load_f64(rec + 16), load_f64(rec + 24)},
          Point2{load_f64(rec + 32), load_f64(rec + 40)}};
}

void z_range_at(const CellsView& view, std::uint32_t index, double& z_min, double& z_max) noexcept {
  const unsigned char* rec = record(view, index);
  z_min = load_f64(rec + 48);
  z_max = load_f64(rec + 56);
}

CellGeometry cell_at(const CellsView& view, std::uint32_t index) noexcept {
  CellGeometry c;
  c.triangle = triangle_at(view, index);
  z_range_at(view, index, c.z_min, c.z_max);
  const unsigned char* rec = record(view, index);
  for (int k = 0; k < 3; ++k) c.neighbours[k] = load_u32(rec + 64 + 4 * k);
  return c;
}

}  // namespace urbanpvs::runtime::detail
