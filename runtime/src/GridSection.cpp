// SPDX-License-Identifier: MIT
// The grid section: the point-location index (FORMAT.md, "grid").
#include <algorithm>
#include <cmath>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 48;

bool list_contains(const GridIndex& g, std::size_t grid_cell, std::uint32_t cell) noexcept {
  std::uint32_t lo = g.offsets[grid_cell];
  std::uint32_t hi = g.offsets[grid_cell + 1];
  while (lo < hi) {  // lists are ascending: binary search
    const std::uint32_t mid = lo + (hi - lo) / 2;
    const std::uint32_t v = g.entries[mid];
    if (v == cell) return true;
    if (v < cell) {
      lo = mid + 1;
    } else {
      hi = mid;
    }
  }
  return false;
}

}  // namespace

std::vector<unsigned char> write_grid(const BuiltGrid& grid) {
  if (grid.entries.size() > UINT32_MAX - 1) {
    throw PvsWriteError("grid: more than 2^32 - 2 point-location entries");
  }
  ByteWriter w;
  const GridGeometry& g = grid.geometry;
  w.f64(g.origin_x);
  w.f64(g.origin_y);
  w.f64(g.size_x);
  w.f64(g.size_y);
  w.u32(g.nx);
  w.u32(g.ny);
  w.u32(static_cast<std::uint32_t>(grid.entries.size()));
  w.u32(0);
  for (std::uint64_t o : grid.offsets) w.u32(static_cast<std::uint32_t>(o));
  for (std::uint32_t e : grid.entries) w.u32(e);
  return std::move(w.bytes());
}

bool read_grid(const SectionBytesView& in, const CellTable& cells, GridIndex& out,
               const char*& detail) {
  ByteReader r(in.data, in.size);
  GridGeometry& g = out.geometry;
  std::uint32_t reserved, entry_count;
  if (!r.f64(g.origin_x) || !r.f64(g.origin_y) || !r.f64(g.size_x) || !r.f64(g.size_y) ||
      !r.u32(g.nx) || !r.u32(g.ny) || !r.u32(entry_count) || !r.u32(reserved) || reserved != 0) {
    detail = "grid: section shorter than its header";
    return false;
  }
  if (!std::isfinite(g.origin_x) || !std::isfinite(g.origin_y) || !std::isfinite(g.size_x) ||
      !std::isfinite(g.size_y) || !(g.size_x > 0) || !(g.size_y > 0) || g.nx == 0 || g.ny == 0) {
    detail = "grid: bad geometry";
    return false;
  }
  std::uint64_t grid_cells, table_bytes;
  if (!checked_mul(g.nx, g.ny, grid_cells) ||
      !checked_mul(grid_cells + 1 + std::uint64_t{entry_count}, 4, table_bytes) ||
      table_bytes > r.remaining() || (table_bytes != r.remaining() && !in.allow_extension)) {
    detail = "grid: size does not match the section length";
    return false;
  }
  // Copied out of the file (bounded by the section length): queries read one grid whatever the
  // file's version.
  const unsigned char* offsets = in.data + kHeaderSize;
  out.offsets.resize(static_cast<std::size_t>(grid_cells + 1));
  for (std::size_t c = 0; c < out.offsets.size(); ++c) out.offsets[c] = load_u32(offsets + 4 * c);
  out.entries.resize(entry_count);
  const unsigned char* entries = offsets + 4 * (grid_cells + 1);
  for (std::size_t e = 0; e < entry_count; ++e) out.entries[e] = load_u32(entries + 4 * e);
  if (out.offsets[0] != 0) {
    detail = "grid: first offset not zero";
    return false;
  }
  for (std::uint64_t c = 0; c < grid_cells; ++c) {
    const std::uint32_t begin = out.offsets[c];
    const std::uint32_t end = out.offsets[c + 1];
    if (end < begin || end > entry_count) {
      detail = "grid: offsets not increasing";
      return false;
    }
    for (std::uint32_t e = begin; e < end; ++e) {
      const std::uint32_t v = out.entries[e];
      if (v >= cells.count || (e > begin && v <= out.entries[e - 1])) {
        detail = "grid: cell list not ascending or out of range";
        return false;
      }
    }
  }
  if (out.offsets[grid_cells] != entry_count) {
    detail = "grid: last offset is not the entry count";
    return false;
  }
  // Exactly the writer's grid: every cell is listed in every grid cell its box maps to, and the
  // entry count leaves room for nothing else. locate() relies on the first half.
  std::uint64_t expected_entries = 0;
  for (std::uint32_t i = 0; i < cells.count; ++i) {
    const GridRange range = triangle_grid_range(g, cells.shapes[i].triangle);
    expected_entries += std::uint64_t{range.x1 - range.x0 + 1} * (range.y1 - range.y0 + 1);
    if (expected_entries > entry_count) break;  // bounds the work on hostile input
    for (std::uint32_t y = range.y0; y <= range.y1; ++y) {
      for (std::uint32_t x = range.x0; x <= range.x1; ++x) {
        if (!list_contains(out, std::size_t{y} * g.nx + x, i)) {
          detail = "grid: a cell is missing from the point-location index";
          return false;
        }
      }
    }
  }
  if (expected_entries != entry_count) {
    detail = "grid: the point-location index does not match the cells";
    return false;
  }
  return true;
}

bool build_grid_index(const CellTable& cells, GridIndex& out, const char*& detail) {
  std::vector<std::array<Point2, 3>> triangles(cells.count);
  for (std::uint32_t i = 0; i < cells.count; ++i) triangles[i] = cells.shapes[i].triangle;
  BuiltGrid grid = build_grid(triangles, cells.grid_density);
  if (grid.entries.size() >= UINT32_MAX) {
    detail = "cells: the point-location grid would exceed 2^32 entries";
    return false;
  }
  out.geometry = grid.geometry;
  out.offsets.resize(grid.offsets.size());
  for (std::size_t c = 0; c < grid.offsets.size(); ++c) {
    out.offsets[c] = static_cast<std::uint32_t>(grid.offsets[c]);  // <= entries.size()
  }
  out.entries = std::move(grid.entries);
  return true;
}

}  // namespace urbanpvs::runtime::detail
