// SPDX-License-Identifier: MIT
// What an engine does with the installed runtime: load a .pvs, locate the camera, draw what
// is visible, and stream: when the camera crosses into the next cell, load what enters view
// and unload what leaves it.
#include <cstdio>

#include "urbanpvs/runtime.hpp"
#include "urbanpvs/urbanpvs.h"

int main(int argc, char** argv) {
  namespace rt = urbanpvs::runtime;
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s FILE.pvs\n", argv[0]);
    return 2;
  }
  rt::PvsFile file;
  rt::LoadError error;
  if (rt::PvsFile::open_file(argv[1], file, {}, &error) != rt::Status::kOk) {
    std::fprintf(stderr, "consumer: %s: %s\n", argv[1], error.detail);
    return 1;
  }
  const auto camera = file.input_to_local(85012.0, 446002.0, 0.25);  // input CRS
  const std::uint32_t cell = file.locate(camera[0], camera[1], camera[2]);
  if (cell == rt::kNoCell) {
    std::fprintf(stderr, "consumer: camera outside every cell\n");
    return 1;
  }
  rt::PvsDecoder visible(file);
  if (visible.decode(cell) != rt::Status::kOk) return 1;
  std::printf("consumer: cell %u sees %zu objects:", cell, visible.size());
  for (std::uint32_t object : visible) {
    rt::ObjectInfo info;
    file.object(object, info);
    std::printf(" %.*s", static_cast<int>(info.source_id.size()), info.source_id.data());
  }
  std::printf("\n");

  // The camera walks into a neighbouring cell: pvs_delta says what to load and what to drop.
  rt::CellGeometry here;
  if (file.cell(cell, here) != rt::Status::kOk) return 1;
  std::uint32_t next = rt::kNoCell;
  for (std::uint32_t n : here.neighbours)
    if (n != rt::kNoCell && next == rt::kNoCell) next = n;
  if (next == rt::kNoCell) {
    std::fprintf(stderr, "consumer: cell %u has no neighbour to walk to\n", cell);
    return 1;
  }
  // The camera steps to the middle of that cell: located from the cell it was in.
  rt::CellGeometry there;
  if (file.cell(next, there) != rt::Status::kOk) return 1;
  const double mx = (there.triangle[0].x + there.triangle[1].x + there.triangle[2].x) / 3;
  const double my = (there.triangle[0].y + there.triangle[1].y + there.triangle[2].y) / 3;
  if (file.locate_from(cell, mx, my, 0.5 * (there.z_min + there.z_max)) != next) return 1;
  const std::size_t before = visible.size();
  rt::PvsDecoder stream(file);
  if (stream.decode_delta(cell, next) != rt::Status::kOk) return 1;
  std::printf("consumer: into cell %u: load %zu, unload %zu, now %zu visible\n", next,
              stream.entered().size, stream.left().size, stream.size());
  // What was loaded, plus what enters, minus what leaves, is what the next cell sees.
  if (before + stream.entered().size - stream.left().size != stream.size()) return 1;
  for (std::uint32_t object : stream.entered())
    if (!file.is_visible(next, object) || file.is_visible(cell, object)) return 1;
  for (std::uint32_t object : stream.left())
    if (file.is_visible(next, object) || !file.is_visible(cell, object)) return 1;

  // The C API is installed too.
  urbanpvs_file* c_file = nullptr;
  if (urbanpvs_open_file(argv[1], &c_file) != URBANPVS_OK) return 1;
  const bool same = urbanpvs_locate(c_file, camera[0], camera[1], camera[2]) == cell;
  urbanpvs_close(c_file);
  return same ? 0 : 1;
}
