// SPDX-License-Identifier: MIT
// What an engine does with the installed runtime: load a .pvs, locate the camera, draw what
// is visible.
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
  // The C API is installed too.
  urbanpvs_file* c_file = nullptr;
  if (urbanpvs_open_file(argv[1], &c_file) != URBANPVS_OK) return 1;
  const bool same = urbanpvs_locate(c_file, camera[0], camera[1], camera[2]) == cell;
  urbanpvs_close(c_file);
  return same ? 0 : 1;
}
