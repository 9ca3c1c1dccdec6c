// SPDX-License-Identifier: MIT
// Validation of a whole file: container first, then each section in dependency order
// (grid and pvs are checked against cells and objects).
#include <algorithm>
#include <new>

#include "PvsFileData.hpp"
#include "urbanpvs/runtime/Format.hpp"

namespace urbanpvs::runtime::detail {
namespace {

using format::SectionId;

Status fail(LoadError& error, Status status, const char* detail, SectionId section) {
  error = {status, static_cast<std::uint32_t>(section), detail};
  return status;
}

const SectionInfo* find_section(const ContainerInfo& c, SectionId id) noexcept {
  for (const SectionInfo& s : c.sections) {
    if (s.id == static_cast<std::uint32_t>(id)) return &s;
  }
  return nullptr;
}

Status load_sections(PvsFileData& file, LoadError& error) {
  const ContainerInfo& c = file.container;
  // A newer minor version may append fields to known sections; a file of our version may not.
  const bool extension = c.minor > format::kMinorVersion;
  constexpr SectionId kRequired[5] = {SectionId::kMetadata, SectionId::kObjects, SectionId::kCells,
                                      SectionId::kGrid, SectionId::kPvs};
  SectionBytesView views[5];
  for (int i = 0; i < 5; ++i) {
    const SectionInfo* s = find_section(c, kRequired[i]);
    if (s == nullptr) {
      return fail(error, Status::kMissingSection, "required section missing", kRequired[i]);
    }
    views[i] = {file.data + s->offset, static_cast<std::size_t>(s->length), extension};
  }
  const char* detail = "";
  if (!read_metadata(views[0], file.metadata, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kMetadata);
  }
  if (!read_objects(views[1], file.objects, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kObjects);
  }
  if (!read_cells(views[2], file.cells, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kCells);
  }
  if (!read_grid(views[3], file.cells, file.grid, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kGrid);
  }
  if (!read_pvs(views[4], file.cells.count, file.objects.count, file.pvs, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kPvs);
  }
  file.geodetic_frame = GeodeticFrame(file.metadata.frame.geodetic_origin);
  const std::size_t half = std::max<std::size_t>(file.pvs.max_pvs_size, 1);
  file.decode_buffer_size = file.pvs.max_chain >= 2 ? 2 * half : half;
  return Status::kOk;
}

}  // namespace

Status load(PvsFileData& file, const LoadOptions& options, LoadError& error) noexcept {
  error = {};
  try {
    const Status status =
        read_container(file.data, file.size, options.verify_checksums, file.container, error);
    if (status != Status::kOk) return status;
    return load_sections(file, error);
  } catch (const std::bad_alloc&) {
    error = {Status::kOutOfMemory, 0, "out of memory while loading"};
    return Status::kOutOfMemory;
  }
}

}  // namespace urbanpvs::runtime::detail
