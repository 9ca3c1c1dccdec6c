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

/// The sections a file of `major` needs, in table order: 1.x stores its grid (id 4), 2.x builds
/// it at load from the cells.
struct Layout {
  const SectionId* ids;
  int count;
};
Layout required_sections(std::uint16_t major) noexcept {
  static constexpr SectionId kV1[5] = {SectionId::kMetadata, SectionId::kObjects, SectionId::kCells,
                                       SectionId::kGrid, SectionId::kPvs};
  static constexpr SectionId kV2[4] = {SectionId::kMetadata, SectionId::kObjects, SectionId::kCells,
                                       SectionId::kPvs};
  return major == 1 ? Layout{kV1, 5} : Layout{kV2, 4};
}

Status load_sections(PvsFileData& file, const LoadOptions& options, LoadError& error) {
  const ContainerInfo& c = file.container;
  // A newer minor version may append fields to known sections; a file of our version may not.
  const bool extension = c.minor > format::latest_minor(c.major);
  const Layout layout = required_sections(c.major);
  SectionBytesView views[5];
  for (int i = 0; i < layout.count; ++i) {
    const SectionInfo* s = find_section(c, layout.ids[i]);
    if (s == nullptr) {
      return fail(error, Status::kMissingSection, "required section missing", layout.ids[i]);
    }
    views[i] = {file.data + s->offset, static_cast<std::size_t>(s->length), extension};
  }
  const SectionBytesView& pvs = views[layout.count - 1];
  const char* detail = "";
  if (!read_metadata(views[0], file.metadata, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kMetadata);
  }
  if (!read_objects(views[1], file.objects, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kObjects);
  }
  if (c.major == 1) {
    if (!read_cells_v1(views[2], file.cells, detail)) {
      return fail(error, Status::kMalformedSection, detail, SectionId::kCells);
    }
    if (!read_grid(views[3], file.cells, file.grid, detail)) {
      return fail(error, Status::kMalformedSection, detail, SectionId::kGrid);
    }
  } else if (!read_cells_v2(views[2], file.cells, detail) ||
             !build_grid_index(file.cells, file.grid, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kCells);
  }
  PvsExpansion* expansion = options.expand_pvs ? &file.expanded : nullptr;
  const bool coded = (c.required_features & format::kFeatureCodedPvs) != 0;
  if (!read_pvs(pvs, file.cells.count, file.objects.count, coded, file.cells.neighbours.data(),
                file.pvs, expansion, detail)) {
    return fail(error, Status::kMalformedSection, detail, SectionId::kPvs);
  }
  if (expansion != nullptr) copy_shapes_into_records(file.cells, *expansion);
  build_locate_index(file.grid, expansion, file.locate);
  if (const SectionInfo* s = c.major >= 2 ? find_section(c, SectionId::kPayloads) : nullptr) {
    const SectionBytesView view{file.data + s->offset, static_cast<std::size_t>(s->length),
                                extension};
    if (!read_payloads(view, file.objects.count, file.payloads, detail)) {
      return fail(error, Status::kMalformedSection, detail, SectionId::kPayloads);
    }
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
    return load_sections(file, options, error);
  } catch (const std::bad_alloc&) {
    error = {Status::kOutOfMemory, 0, "out of memory while loading"};
    return Status::kOutOfMemory;
  }
}

}  // namespace urbanpvs::runtime::detail
