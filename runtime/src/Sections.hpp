// SPDX-License-Identifier: MIT
#pragma once

// Reading and writing of the sections (FORMAT.md, one heading each). Each reader checks
// its section completely against its length and reports the failed check in `detail`; the
// views it fills point into the caller's buffer. Readers may throw std::bad_alloc (the loader
// turns it into Status::kOutOfMemory); writers throw PvsWriteError on size limits.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "HugePages.hpp"
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
/// The cells of a validated file, decoded whatever the version: locate() tests a cell's triangle
/// and z range from one 64-byte record, and cell() adds the neighbours.
struct CellShape {
  std::array<Point2, 3> triangle;
  double z_min;
  double z_max;
};
struct CellTable {
  LargeVector<CellShape> shapes;
  LargeVector<std::array<std::uint32_t, 3>> neighbours;
  std::uint32_t count = 0;
  /// Grid cells per view cell of the point-location grid (stored in 2.x, built at load).
  double grid_density = 1;
};
/// Version 1.x: fixed 76-byte records (FORMAT.md, "cells, version 1").
std::vector<unsigned char> write_cells_v1(const std::vector<CellRecord>& cells);
bool read_cells_v1(const SectionBytesView& in, CellTable& out, const char*& detail);
/// Version 2.x: an indexed mesh of quantized vertices (FORMAT.md, "cells, version 2").
std::vector<unsigned char> write_cells_v2(const std::vector<CellRecord>& cells,
                                          const EncodeOptions& options);
bool read_cells_v2(const SectionBytesView& in, CellTable& out, const char*& detail);
/// The cells as a 2.x reader sees them: quantized and with derived neighbours. The writer plans
/// the PVS encoding over these neighbours, so writer and reader agree on the mesh.
CellGeometry cell_at(const CellTable& table, std::uint32_t index) noexcept;

// --- grid --------------------------------------------------------------------------------------
/// The point-location grid, owned: read and checked from a 1.x file's grid section, or built at
/// load from a 2.x file's cells with the same function the 1.x writer used.
struct GridIndex {
  GridGeometry geometry;
  LargeVector<std::uint32_t> offsets;  ///< nx * ny + 1
  LargeVector<std::uint32_t> entries;
};
std::vector<unsigned char> write_grid(const BuiltGrid& grid);
/// Also checks the grid is exactly the one build_grid's indexing gives for `cells`.
bool read_grid(const SectionBytesView& in, const CellTable& cells, GridIndex& out,
               const char*& detail);
/// Builds the grid of a 2.x file from its cells; false (with `detail`) when it does not fit the
/// 32-bit entries.
bool build_grid_index(const CellTable& cells, GridIndex& out, const char*& detail);

// --- payloads (2.1, optional) -------------------------------------------------------------------
struct PayloadsView {
  std::string_view key;                    ///< the attribute or tag the values came from
  const unsigned char* offsets = nullptr;  ///< object count + 1 little-endian u32
  const unsigned char* data = nullptr;
  bool present = false;
};
std::vector<unsigned char> write_payloads(const std::string& key,
                                          const std::vector<ObjectRecord>& objects);
bool read_payloads(const SectionBytesView& in, std::uint32_t object_count, PayloadsView& out,
                   const char*& detail);
/// Payload of object `index` (< object count) of a validated view; empty when there is none.
std::string_view payload_at(const PayloadsView& view, std::uint32_t index) noexcept;

// --- pvs ---------------------------------------------------------------------------------------
struct PvsView {
  PvsSection section;
  std::uint32_t max_pvs_size = 0;
  std::uint32_t max_chain = 0;  ///< longest diff chain actually present
  std::uint64_t total_entries = 0;
};
/// A cell's neighbours, as the cells section gives them.
using Neighbours = std::array<std::uint32_t, 3>;
/// The bake's PVS lists, held as vectors in its cells or given by its pvs_source.
class PvsLists {
 public:
  explicit PvsLists(const PvsBake& bake) : bake_(bake) {}
  std::size_t size() const noexcept { return bake_.cells.size(); }
  /// Cell `cell`'s list: the cell's own vector, or `buffer` filled by the source.
  const std::vector<std::uint32_t>& get(std::uint32_t cell,
                                        std::vector<std::uint32_t>& buffer) const {
    if (!bake_.pvs_source) return bake_.cells[cell].pvs;
    bake_.pvs_source(cell, buffer);
    return buffer;
  }

 private:
  const PvsBake& bake_;
};
/// `coded`: the 2.2 layout (exp-Golomb gaps, block index, neighbour-slot references), else the
/// 2.0 one. `neighbours` (one per cell) are the ones a reader will see: the candidates of diff
/// references, and in the coded layout the targets of their slots.
std::vector<unsigned char> write_pvs(const PvsLists& lists,
                                     const std::vector<Neighbours>& neighbours,
                                     const EncodeOptions& options, bool coded);
/// Every cell's PVS decoded into one array (LoadOptions::expand_pvs), a record per cell, each
/// starting on a 64-byte boundary of `ids`: the cell's CellShape (kShapeWords), its index, its
/// PVS size, the sorted ids, then padding to a whole number of kRecordWords. A random locate
/// reads the shape and the found cell's first ids from the same lines, fetched at once
/// (LocateIndex.hpp). `offsets[c]` is where cell c's ids begin; offsets[cell_count] is the
/// array's size.
struct PvsExpansion {
  static constexpr std::size_t kRecordWords = 16;  ///< 64 bytes
  static constexpr std::size_t kShapeWords = 16;   ///< sizeof(CellShape) / 4
  static constexpr std::size_t kHeaderWords = kShapeWords + 2;
  LargeVector<std::uint32_t> ids;
  LargeVector<std::uint64_t> offsets;
  bool empty() const noexcept { return offsets.empty(); }
  std::uint32_t size(std::uint32_t cell) const noexcept {
    return ids[static_cast<std::size_t>(offsets[cell]) - 1];
  }
  /// Where cell c's record begins, in records (64-byte units).
  std::uint64_t record(std::uint32_t cell) const noexcept {
    return (offsets[cell] - kHeaderWords) / kRecordWords;
  }
};
static_assert(sizeof(CellShape) == 4 * PvsExpansion::kShapeWords);
/// Decodes every cell once: sorted, in range, counts consistent, chains within bounds. When
/// `expansion` is given, keeps the decoded lists there.
/// `coded`: the file sets format::kFeatureCodedPvs, and `neighbours` (cell_count entries, the
/// cells section's) are what its diffs' neighbour slots name.
bool read_pvs(const SectionBytesView& in, std::uint32_t cell_count, std::uint32_t object_count,
              bool coded, const Neighbours* neighbours, PvsView& out, PvsExpansion* expansion,
              const char*& detail);

}  // namespace urbanpvs::runtime::detail
