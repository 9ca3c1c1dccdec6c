// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// The .pvs writer, used by the offline preprocessor (and by tests for round trips). Unlike the
/// reader it reports errors with exceptions (PvsWriteError): it runs offline, next to code that
/// already throws, and a message with the offending index is worth more there than a code.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "urbanpvs/runtime/FileIo.hpp"
#include "urbanpvs/runtime/Types.hpp"

namespace urbanpvs::runtime {

/// Coordinate frame of the bake. Coordinates in the bake (objects, cells) are LOCAL:
/// local = input − origin, where "input" is the input CRS for projected inputs and the
/// east-north-up frame at geodetic_origin for geographic (WGS84) ones.
struct Frame {
  std::string crs;          ///< input CRS, e.g. "EPSG:7415"; may be empty. UTF-8.
  bool geographic = false;  ///< the input was WGS84 lon/lat; geodetic_origin is then meaningful
  GeodeticOrigin geodetic_origin{};
  std::array<double, 3> origin{};  ///< local-frame origin in input coordinates (finite)
};

struct Metadata {
  Frame frame;
  BakeSettings settings;
  /// Free-form (key, value) pairs, stored in this order; UTF-8, each < 4 GiB.
  std::vector<std::pair<std::string, std::string>> properties;
};

/// An object (building). Its index is its position in PvsBake::objects.
struct ObjectRecord {
  std::string source_id;  ///< id in the input (e.g. "NL.IMBAG.Pand.0503100000012345"), UTF-8
  Bbox bbox{};            ///< local frame, finite, min <= max per axis
  /// The user's value for this object (PvsBake::payload_key), UTF-8; empty when it has none.
  std::string payload;
};

/// A view cell and its PVS. Its index is its position in PvsBake::cells.
struct CellRecord {
  std::array<Point2, 3> triangle{};  ///< local frame, finite
  double z_min = 0;                  ///< prism bottom (local frame), finite, <= z_max
  double z_max = 0;                  ///< prism top (local frame), finite
  /// neighbours[i] is the cell across the edge triangle[i] → triangle[(i+1)%3], or kNoCell.
  std::array<std::uint32_t, 3> neighbours{kNoCell, kNoCell, kNoCell};
  /// Visible objects: strictly increasing indices into PvsBake::objects.
  std::vector<std::uint32_t> pvs;
};

/// Everything a .pvs file holds, as the preprocessor fills it.
struct PvsBake {
  Metadata meta;
  std::vector<ObjectRecord> objects;  ///< fewer than 2^32 - 1
  std::vector<CellRecord> cells;      ///< fewer than 2^32 - 1
  /// The attribute or tag the objects' payloads came from (UTF-8). Non-empty: the file gets a
  /// payloads section and is version 2.1 (format_major 2 only); empty: every payload must be.
  std::string payload_key;
  /// For bakes whose lists are too many to hold as vectors (a city whose buildings mostly have
  /// no height: every cell sees them all). When set, every cell's `pvs` must be empty, and the
  /// writer asks this for cell i's list instead (the same strictly increasing indices), in no
  /// fixed order: to validate it, to encode it, and as a diff candidate of its neighbours (about
  /// 5 times per cell at the default diff chain, up to about 20 at the longest), so it should
  /// decode from compact storage quickly.
  /// The bytes written are those of the same lists given as vectors.
  std::function<void(std::uint32_t cell, std::vector<std::uint32_t>& pvs)> pvs_source;
};

/// How the gaps of the PVS lists are coded.
enum class PvsCoding : std::uint8_t {
  /// Varint gaps and a u32 offset per cell: format 2.0/2.1, for readers of those versions.
  kVarint,
  /// Exp-Golomb gaps, their order chosen per list, derived diff counts, neighbour-slot diff
  /// references and a block index of u16 offsets: format 2.2 (required feature
  /// kFeatureCodedPvs). The PVS section is 25-38% smaller on the bakes of runtime/README.md.
  kExpGolomb,
};

/// Encoding choices. The defaults are the measured best trade-off (see runtime/README.md).
struct EncodeOptions {
  /// Store bounding boxes as float32 (rounded outwards, so boxes only grow: ≤ 0.5 mm at 4 km
  /// from the origin) or exactly as float64.
  bool bbox_float32 = true;
  /// Longest chain of diff-encoded cells (0 = every cell stored in full, at most
  /// format::kMaxDiffChain). 1 keeps lookups to one decode and one merge pass.
  std::uint32_t max_diff_chain = 1;
  /// A cell is stored as a diff only when the diff is at most this fraction of its smallest
  /// full encoding. Lower values make more full "key" cells, so diffs stay between close
  /// neighbours: smaller AND faster to apply, down to about 0.25 (README, measurements).
  double diff_threshold = 0.3;
  /// Point-location grid resolution: about this many grid cells per view cell (in (0, 64]).
  double grid_cells_per_cell = 1.0;
  /// Major format version to write: 2 (the default: cells as an indexed mesh of millimetre
  /// vertices, the grid built at load) or 1 (float64 cell records and a stored grid, for
  /// engines that still ship a 1.x reader; this library reads both).
  std::uint16_t format_major = 2;
  /// PVS coding of a format_major 2 file (1.0 files are always varint coded).
  PvsCoding pvs_coding = PvsCoding::kExpGolomb;
};

/// Thrown by the writer; what() names the offending element and the reason, or the path.
class PvsWriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Checks `bake` against the constraints documented above; returns "" when valid, else the
/// first problem ("cell 12: pvs not strictly increasing at position 3").
std::string validate(const PvsBake& bake);

/// Encodes `bake` as a .pvs file. Deterministic: the same bake and options always give the same
/// bytes (no pointers, hashes of addresses, clocks or unordered containers are involved).
/// Throws PvsWriteError when validate() fails or a size limit of the format is exceeded.
std::vector<std::byte> encode(const PvsBake& bake, const EncodeOptions& options = {});

}  // namespace urbanpvs::runtime
