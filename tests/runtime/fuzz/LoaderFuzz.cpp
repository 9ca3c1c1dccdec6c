// SPDX-License-Identifier: MIT
// Fuzz entry point for the .pvs loader: whatever the bytes, open() must not crash, hang or read
// out of bounds, and a file it accepts must answer every query consistently. Each input is
// loaded twice: with checksums (what applications do) and without, so mutations reach the
// structural validation behind the checksums (a hostile file can carry valid checksums).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>

#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

using urbanpvs::runtime::CellGeometry;
using urbanpvs::runtime::kNoCell;
using urbanpvs::runtime::LoadOptions;
using urbanpvs::runtime::ObjectInfo;
using urbanpvs::runtime::PvsFile;
using urbanpvs::runtime::Status;

void check(bool ok) {
  if (!ok) std::abort();  // an invariant of an accepted file does not hold
}

void exercise_cells(const PvsFile& file) {
  std::vector<std::uint32_t> buffer(file.decode_buffer_size());
  // A decoder that caches cells decodes a diff as a merge against its cached reference.
  urbanpvs::runtime::PvsDecoder cached(file, 8);
  const std::uint32_t cells = file.cell_count() < 4096 ? file.cell_count() : 4096;
  for (std::uint32_t c = 0; c < cells; ++c) {
    CellGeometry g;
    check(file.cell(c, g) == Status::kOk);
    std::size_t n = 0;
    check(file.decode_pvs(c, buffer.data(), buffer.size(), n) == Status::kOk);
    check(n == file.pvs_size(c) && n <= file.max_pvs_size());
    for (std::size_t i = 0; i < n; ++i) {
      check(buffer[i] < file.object_count() && (i == 0 || buffer[i] > buffer[i - 1]));
      if (i < 64) check(file.is_visible(c, buffer[i]));
    }
    if (n > 0 && buffer[0] > 0) check(!file.is_visible(c, buffer[0] - 1));
    urbanpvs::runtime::PvsEncodingInfo info;
    check(file.pvs_encoding(c, info) == Status::kOk);
    if (info.reference != kNoCell) check(cached.decode(info.reference) == Status::kOk);
    check(cached.decode(c) == Status::kOk && cached.size() == n &&
          std::equal(cached.begin(), cached.end(), buffer.begin()));
    // The centroid of a non-degenerate cell is inside some cell (maybe a lower-index one).
    const double x = (g.triangle[0].x + g.triangle[1].x + g.triangle[2].x) / 3;
    const double y = (g.triangle[0].y + g.triangle[1].y + g.triangle[2].y) / 3;
    const std::uint32_t found = file.locate(x, y, g.z_min);
    check(found == kNoCell || found < file.cell_count());
    check(file.locate_xy(x, y) == kNoCell || file.locate_xy(x, y) < file.cell_count());
    // From a hint (this cell, a neighbour, none, out of range): none, or a cell whose prism
    // holds the point; the hint itself when the hint is locate()'s answer.
    for (const std::uint32_t hint : {c, g.neighbours[0], kNoCell, file.cell_count() + 7}) {
      const std::uint32_t from = file.locate_from(hint, x, y, g.z_min);
      if (from == kNoCell) continue;
      urbanpvs::runtime::CellGeometry h;
      check(file.cell(from, h) == Status::kOk && g.z_min >= h.z_min && g.z_min <= h.z_max &&
            urbanpvs::runtime::triangle_contains(h.triangle, x, y));
    }
    if (found != kNoCell) check(file.locate_from(found, x, y, g.z_min) == found);
  }
  check(file.locate(std::nan(""), 0, 0) == kNoCell);
  // Set operations across neighbours: sizes add up, every entry is in range.
  urbanpvs::runtime::PvsDecoder decoder(file);
  for (std::uint32_t c = 0; c + 1 < cells && c < 64; ++c) {
    const std::uint32_t pair[2] = {c, c + 1};
    check(decoder.decode_union(pair, 2) == Status::kOk);
    check(decoder.size() >= file.pvs_size(c) && decoder.size() >= file.pvs_size(c + 1) &&
          decoder.size() <= std::size_t{file.pvs_size(c)} + file.pvs_size(c + 1));
    for (std::uint32_t o : decoder) check(o < file.object_count());
    check(decoder.decode_delta(c, c + 1) == Status::kOk);
    check(std::size_t{file.pvs_size(c)} + decoder.entered().size - decoder.left().size ==
          file.pvs_size(c + 1));
  }
  std::size_t ignored = 0;
  check(file.decode_pvs(file.cell_count(), buffer.data(), buffer.size(), ignored) ==
        Status::kOutOfRange);
}

void exercise(const PvsFile& file) {
  const auto frame = file.frame();
  check(frame.crs.size() < file.file_size() + 1);
  for (std::size_t i = 0; i < file.property_count(); ++i) {
    std::string_view k, v;
    check(file.property(i, k, v) == Status::kOk);
  }
  const std::uint32_t objects = file.object_count() < 4096 ? file.object_count() : 4096;
  for (std::uint32_t i = 0; i < objects; ++i) {
    ObjectInfo o;
    check(file.object(i, o) == Status::kOk && o.bbox[0] <= o.bbox[3]);
  }
  std::array<double, 3> local{};
  check(file.geodetic_to_local(52, 4.3, 0, local) ==
        (frame.geographic ? Status::kOk : Status::kNotGeographic));
  exercise_cells(file);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (bool verify : {true, false}) {
    PvsFile file;
    LoadOptions options;
    options.verify_checksums = verify;
    if (PvsFile::open(data, size, file, options) == Status::kOk) exercise(file);
  }
  return 0;
}
