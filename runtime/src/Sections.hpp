// SPDX-License-Identifier: MIT
#pragma once

// Reading and writing of the five sections (FORMAT.md, one heading each). Each reader checks
// its section completely against its length and reports the failed check in `detail`; the
// views it fills point into the caller's buffer. Readers may throw std::bad_alloc (the loader
// turns it into Status::kOutOfMemory); writers throw PvsWriteError on size limits.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <utility>
#include <vector>

#include "PointLocationGrid.hpp"
#include "PvsCodec.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace urbanpvs::runtime::detail {

/// A section's bytes, and whether bytes after the known fields are tolerated (only in files of
/// a newer minor version, which may append fields).
struct SectionBytesView {
  const unsigned char* data = nullptr;
  std::size_t size = 0;
  bool allow_extension = false;
};

// --- metadata ----------------------------------------------------------------------------------
struct MetadataView {
  FrameInfo frame;
  BakeSettings settings;
  std::vector<std::pair<std::string_view, std::string_view>> properties;
};
std::vector<unsigned char> write_metadata(const Metadata& meta);
bool read_metadata(const SectionBytesView& in, MetadataView& out, const char*& detail);

// --- objects -----------------------------------------------------------------------------------
struct ObjectsView {
  const unsigned char* records = nullptr;
  const unsigned char* strings = nullptr;
  std::uint64_t strings_size = 0;
  std::uint32_t count = 0;
  std::uint8_t bbox_width = 0;  ///< 4 or 8
  std::size_t record_size = 0;
};
std::vector<unsigned char> write_objects(const std::vector<ObjectRecord>& objects, bool float32);
bool read_objects(const SectionBytesView& in, ObjectsView& out, const char*& detail);
/// Object `index` (< view.count) of a validated view.
ObjectInfo object_at(const ObjectsView& view, std::uint32_t index) noexcept;

// --- cells -------------------------------------------------------------------------------------
struct CellsView {
  const unsigned char* records = nullptr;
  std::uint32_t count = 0;
};
std::vector<unsigned char> write_cells(const std::vector<CellRecord>& cells);
bool read_cells(const SectionBytesView& in, CellsView& out, const char*& detail);
/// Triangle of cell `index` (< view.count): read straight from the record (locate's hot path).
std::array<Point2, 3> triangle_at(const CellsView& view, std::uint32_t index) noexcept;
CellGeometry cell_at(const CellsView& view, std::uint32_t index) noexcept;
/// z range of cell `index`.
void z_range_at(const CellsView& view, std::uint32_t index, double& z_min, double& z_max) noexcept;

// --- grid --------------------------------------------------------------------------------------
struct GridView {
  GridGeometry geometry;
  const unsigned char* offsets = nullptr;  ///< nx * ny + 1 u32
  const unsigned char* entries = nullptr;
  std::uint32_t entry_count = 0;
};
std::vector<unsigned char> write_grid(const BuiltGrid& grid);
/// Also checks the grid is exactly the one build_grid's indexing gives for `cells`.
bool read_grid(const SectionBytesView& in, const CellsView& cells, GridView& out,
               const char*& detail);

// --- pvs ---------------------------------------------------------------------------------------
struct PvsView {
  PvsSection section;
  std::uint32_t max_pvs_size = 0;
  std::uint32_t max_chain = 0;  ///< longest diff chain actually present
  std::uint64_t total_entries = 0;
};
std::vector<unsigned char> write_pvs(const std::vector<CellRecord>& cells,
                                     const EncodeOptions& options);
/// Decodes every cell once: sorted, in range, counts consistent, chains within bounds.
bool read_pvs(const SectionBytesView& in, std::uint32_t cell_count, std::uint32_t object_count,
              PvsView& out, const char*& detail);

}  // namespace urbanpvs::runtime::detail
