// SPDX-License-Identifier: MIT
#pragma once

/// \file
/// PvsFile: read-only access to a .pvs file held in memory — point location, per-cell PVS and
/// the object / cell tables.
///
/// Safety on untrusted input: open() validates everything before it reports kOk — header,
/// section table, checksums (unless disabled in LoadOptions), every count and offset against the
/// buffer (64-bit, overflow-checked), every string as UTF-8, every cell's PVS encoding (checked
/// to decode sorted, in range and within the diff-chain bound: each full list is decoded once,
/// each diff checked against its reference) and the point-location grid
/// (checked to be exactly the one the writer builds). A buffer that passes never makes a later
/// call read out of bounds; one that fails leaves `out` closed. Every function is noexcept and
/// the library never aborts on bad input. The loader is fuzzed (tests/runtime/fuzz).
///
/// Thread safety: after open() returns, all const member functions may be called concurrently
/// from any number of threads (they only read the buffer; decode_pvs writes only the caller's
/// buffer). open()/move assignment must not race with readers of the same object.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "urbanpvs/runtime/Status.hpp"
#include "urbanpvs/runtime/Types.hpp"

namespace urbanpvs::runtime {

namespace detail {
struct PvsFileData;  // the validated views into the buffer (src/PvsFileData.hpp)
}  // namespace detail

/// What went wrong in open(), for messages ("checksum mismatch in section 'pvs'").
struct LoadError {
  Status status = Status::kOk;
  /// Section concerned (format::SectionId value), 0 when the header is at fault.
  std::uint32_t section_id = 0;
  /// Static English description of the failed check (never null, "" when status is kOk).
  const char* detail = "";
};

struct LoadOptions {
  /// Verify the header and section CRC32Cs. Turning it off only makes sense for fuzzing the
  /// structural validation behind the checksums (which always runs) or for files the caller
  /// has already verified; a corrupted but structurally valid file then loads with wrong data.
  bool verify_checksums = true;
  /// Decode every cell's PVS at load, after validating the file, and keep it: pvs_span() then
  /// returns it in place, and decode() and is_visible() read it without decoding (loading
  /// takes about 2-3 times as long). Costs 4 bytes per PVS entry (total_pvs_entries()), what plain
  /// lists take: the file stays small on disk and on the wire, and memory buys the fastest queries.
  bool expand_pvs = false;
};

/// An object (building) as stored: its source id and its bounding box in the local frame.
struct ObjectInfo {
  std::string_view source_id;  ///< points into the file's buffer; valid while the file is open
  Bbox bbox{};
  /// The user's value for it (payload_key()), UTF-8, pointing into the buffer; empty when the
  /// object has none or the file has no payloads section (before 2.1).
  std::string_view payload;
};

/// The coordinate frame of the file. Stored coordinates are local = input − origin; for a
/// geographic (WGS84) input "input" means the east-north-up frame at geodetic_origin.
struct FrameInfo {
  std::string_view crs;  ///< e.g. "EPSG:7415", may be empty; points into the buffer
  bool geographic = false;
  GeodeticOrigin geodetic_origin{};
  std::array<double, 3> origin{};  ///< local-frame origin, in input coordinates
};

/// One entry of the section table.
struct SectionInfo {
  std::uint32_t id = 0;
  std::uint32_t crc32c = 0;
  std::uint64_t offset = 0;
  std::uint64_t length = 0;
};

/// How one cell's PVS is encoded (for inspection and statistics).
struct PvsEncodingInfo {
  std::uint8_t kind = 0;              ///< format::PvsKind value
  std::uint32_t reference = kNoCell;  ///< reference cell of a kDiff cell, else kNoCell
  std::uint32_t chain_length = 0;     ///< number of kDiff steps to reach a full cell
  std::uint32_t payload_bytes = 0;    ///< bytes of this cell's payload
};

/// A contiguous run of object indices (no ownership).
struct IndexSpan {
  const std::uint32_t* data = nullptr;
  std::size_t size = 0;
  const std::uint32_t* begin() const noexcept { return data; }
  const std::uint32_t* end() const noexcept { return data + size; }
};

class PvsFile {
 public:
  PvsFile() noexcept;
  ~PvsFile();
  PvsFile(PvsFile&& other) noexcept;
  PvsFile& operator=(PvsFile&& other) noexcept;
  PvsFile(const PvsFile&) = delete;
  PvsFile& operator=(const PvsFile&) = delete;

  /// Validates and opens a file held in `data[0, size)`. The bytes are NOT copied: the caller
  /// keeps them alive and unchanged for as long as `out` (or anything it returned) is used. The
  /// buffer needs no particular alignment. On failure `out` is closed and `error` (if given)
  /// says why. Allocates a few small tables (O(sections + metadata entries)) and a scratch
  /// buffer of O(largest PVS) for validation: kOutOfMemory if that fails.
  static Status open(const void* data, std::size_t size, PvsFile& out,
                     const LoadOptions& options = {}, LoadError* error = nullptr) noexcept;

  /// As open(), but `out` takes ownership of `bytes` (moved in; left empty on every path).
  static Status open_owned(std::vector<std::byte>&& bytes, PvsFile& out,
                           const LoadOptions& options = {}, LoadError* error = nullptr) noexcept;

  /// Reads the whole file at `path` (see read_file) and opens it owning the bytes.
  /// kIoError when the file cannot be read. On Linux the bytes, like the tables the library
  /// builds (cell shapes, point-location grid, expanded lists), sit on transparent huge pages
  /// when the system gives them (madvise mode): random lookups then miss the TLB far less.
  static Status open_file(const char* path, PvsFile& out, const LoadOptions& options = {},
                          LoadError* error = nullptr) noexcept;

  /// True after a successful open. Every accessor below requires an open file; on a closed
  /// one counts are 0, lookups answer kNoCell / false and decode_pvs kOutOfRange.
  bool is_open() const noexcept;

  std::uint16_t major_version() const noexcept;
  std::uint16_t minor_version() const noexcept;
  /// Size of the file in bytes (== the buffer size).
  std::size_t file_size() const noexcept;
  std::size_t section_count() const noexcept;
  /// Section table entry `index` (< section_count()); a zeroed entry when out of range.
  SectionInfo section(std::size_t index) const noexcept;

  // --- metadata --------------------------------------------------------------------------------
  FrameInfo frame() const noexcept;
  BakeSettings settings() const noexcept;
  /// Number of free-form key/value properties.
  std::size_t property_count() const noexcept;
  /// Property `index` (< property_count()); kOutOfRange otherwise. Views point into the buffer.
  Status property(std::size_t index, std::string_view& key, std::string_view& value) const noexcept;

  // --- coordinates -----------------------------------------------------------------------------
  /// Input coordinates (CRS of the input, or ENU for geographic inputs) → stored local frame.
  std::array<double, 3> input_to_local(double x, double y, double z) const noexcept;
  /// Stored local frame → input coordinates.
  std::array<double, 3> local_to_input(double x, double y, double z) const noexcept;
  /// WGS84 latitude/longitude (degrees) and height (m) → local frame, as the preprocessor maps
  /// geographic input: x, y east and north of the point's foot on the ellipsoid in the stored
  /// east-north-up frame, z the height minus the frame's z origin (the earth's curvature, 8 cm
  /// at 1 km, is left out so that verticals stay vertical). kNotGeographic when the input was
  /// not geographic.
  Status geodetic_to_local(double lat_deg, double lon_deg, double h_m,
                           std::array<double, 3>& local) const noexcept;

  // --- objects and cells -----------------------------------------------------------------------
  std::uint32_t object_count() const noexcept;
  std::uint32_t cell_count() const noexcept;
  /// Object `index`; kOutOfRange when index >= object_count().
  Status object(std::uint32_t index, ObjectInfo& out) const noexcept;
  /// Whether the file carries a payload per object (a 2.1 payloads section).
  bool has_payloads() const noexcept;
  /// The attribute or tag the payloads came from ("" without payloads); points into the buffer.
  std::string_view payload_key() const noexcept;
  /// Cell `index`; kOutOfRange when index >= cell_count().
  Status cell(std::uint32_t index, CellGeometry& out) const noexcept;

  // --- queries ---------------------------------------------------------------------------------
  /// The cell whose prism contains the local point (x, y, z), or kNoCell. When several cells
  /// contain it (a point on a shared edge or vertex, overlapping or stacked cells) the lowest
  /// cell index wins, so the answer is deterministic. z must lie in [z_min, z_max] of the cell:
  /// a point above or below every prism at (x, y) is outside. Non-finite input → kNoCell.
  /// Typical cost: one grid lookup and 1–5 triangle tests, no allocation.
  std::uint32_t locate(double x, double y, double z) const noexcept;
  /// As locate() but ignoring z (the lowest-index cell whose triangle contains (x, y)).
  std::uint32_t locate_xy(double x, double y) const noexcept;
  /// locate() for a point that moves: `hint` is the cell it was in (the last answer). The hint
  /// cell when its prism contains (x, y, z); else the first of its neighbours whose prism does;
  /// else locate(). So the answer is always a cell whose prism contains the point, or kNoCell
  /// when none does; it differs from locate() only where several prisms contain the point (on
  /// a shared edge or vertex the camera keeps its cell instead of flickering to the lower
  /// index). A walking camera or an agent stays in its cell for many frames and then crosses
  /// into a neighbour: one or a few triangle tests on lines already in cache, no grid lookup.
  /// hint == kNoCell or out of range: locate(). Non-finite input → kNoCell.
  std::uint32_t locate_from(std::uint32_t hint, double x, double y, double z) const noexcept;

  /// Number of objects visible from `cell` (0 when out of range). O(1).
  std::uint32_t pvs_size(std::uint32_t cell) const noexcept;
  /// The largest pvs_size() over all cells.
  std::uint32_t max_pvs_size() const noexcept;
  /// Sum of pvs_size() over all cells (what plain 32-bit id lists would store).
  std::uint64_t total_pvs_entries() const noexcept;
  /// Number of uint32_t slots decode_pvs() needs: max_pvs_size(), or twice that when the file
  /// has chains of two or more diff steps (the second half is decoding scratch).
  std::size_t decode_buffer_size() const noexcept;
  /// Writes the sorted object indices visible from `cell` to `buffer[0, count)`. `capacity`
  /// must be >= decode_buffer_size() (kBufferTooSmall otherwise; the contents of the whole
  /// buffer are unspecified afterwards). No allocation; O(|PVS| × chain length).
  Status decode_pvs(std::uint32_t cell, std::uint32_t* buffer, std::size_t capacity,
                    std::size_t& count) const noexcept;
  /// Whether `object` is in the PVS of `cell` (false when either is out of range). No
  /// allocation and no decode buffer: scans the encoded lists with early exit, or a binary
  /// search of the expanded list (O(log |PVS|)) when the file was opened with expand_pvs.
  bool is_visible(std::uint32_t cell, std::uint32_t object) const noexcept;
  /// Whether the file was opened with LoadOptions::expand_pvs.
  bool is_expanded() const noexcept;
  /// The decoded PVS of `cell` in place (ascending, valid while the file is open), when the
  /// file was opened with expand_pvs: O(1), no copy. kNotExpanded otherwise, kOutOfRange when
  /// cell >= cell_count().
  Status pvs_span(std::uint32_t cell, IndexSpan& out) const noexcept;
  /// How the PVS of `cell` is stored; kOutOfRange when cell >= cell_count().
  Status pvs_encoding(std::uint32_t cell, PvsEncodingInfo& out) const noexcept;

 private:
  static Status open_data(std::unique_ptr<detail::PvsFileData> data, PvsFile& out,
                          const LoadOptions& options, LoadError* error) noexcept;

  friend class PvsDecoder;  // decodes a diff against its reference's cached list

  std::unique_ptr<const detail::PvsFileData> data_;
};

/// A reusable decoder: owns its buffers, allocated once in the constructor, so decoding PVSs in
/// a loop allocates nothing. One decoder per thread; the file must outlive it.
///
/// It keeps the lists of the last `cached_cells` cells it decoded (least recently used out, in
/// sets of 16), each in a slot of decode_buffer_size() entries: cached_cells x
/// decode_buffer_size() x 4 bytes. One slot (the default) serves a camera, which stays in its
/// cell for many frames. A crowd served by one decoder (agents queried in turn, each in its own
/// cell) wants a slot per agent; a cell whose diff reference is cached is then decoded as one
/// merge against it. A file opened with expand_pvs needs no cache: its lists are read in place.
///
/// It also answers what a streaming engine asks (PvsSetOperations.cpp): the union of several
/// cells' PVSs (prefetching around the camera or along a route) and the delta between two
/// cells (what to load and what may be unloaded when the camera crosses). Their storage is
/// allocated once, on the first such call (about object_count() slots for unions, 3 x
/// max_pvs_size() for deltas); later calls allocate nothing.
class PvsDecoder {
 public:
  /// Allocates the cache (at least one slot; 0 counts as 1). If that fails, it tries one slot,
  /// and without that decode() returns kOutOfMemory.
  explicit PvsDecoder(const PvsFile& file, std::size_t cached_cells = 1) noexcept;
  ~PvsDecoder();
  PvsDecoder(const PvsDecoder&) = delete;
  PvsDecoder& operator=(const PvsDecoder&) = delete;

  /// Decodes the PVS of `cell`; the result is in view() until the next call. A cell still in
  /// the cache returns at once; on an expanded file view() points into the file's lists (no
  /// copy).
  Status decode(std::uint32_t cell) noexcept;
  /// The objects visible from any of `cells[0, n)`, ascending and each once, in view() until
  /// the next call. n == 0 gives an empty set. kOutOfRange when a cell is out of range,
  /// kInvalidArgument when cells is null and n > 0 (view() is then empty). O(sum of the
  /// PVS sizes + object_count() / 32).
  Status decode_union(const std::uint32_t* cells, std::size_t n) noexcept;
  /// The camera crosses from cell `from` to cell `to`: entered() is PVS(to) minus PVS(from)
  /// (what to load), left() is PVS(from) minus PVS(to) (what may be unloaded), both ascending;
  /// view() is PVS(to). All three stay until the next call; on an error all are empty.
  /// O(|PVS(from)| + |PVS(to)|).
  Status decode_delta(std::uint32_t from, std::uint32_t to) noexcept;

  /// The last decoded set (empty before the first successful call).
  IndexSpan view() const noexcept { return {result_, size_}; }
  const std::uint32_t* begin() const noexcept { return result_; }
  const std::uint32_t* end() const noexcept { return result_ + size_; }
  std::size_t size() const noexcept { return size_; }
  /// The number of cells the cache holds (0 when its allocation failed).
  std::size_t cached_cells() const noexcept { return slots_; }
  /// After decode_delta(): the objects that came into view and those that went out of it.
  IndexSpan entered() const noexcept { return entered_; }
  IndexSpan left() const noexcept { return left_; }

 private:
  void clear() noexcept;
  bool reserve_sets(std::size_t slots) noexcept;
  /// The PVS of `cell`: in the file when it is expanded, else in a cache slot (decoded into the
  /// least recently used one of its set when missing). Valid until the next fetch.
  Status fetch(std::uint32_t cell, IndexSpan& out) noexcept;
  /// The first slot of the set `cell` maps to.
  std::size_t set_start(std::uint32_t cell) const noexcept;
  /// The cache slot holding `cell`, or slots_ when none does.
  std::size_t find_slot(std::uint32_t cell) const noexcept;
  std::uint32_t* slot_data(std::size_t slot) const noexcept {
    return buffer_.get() + slot * capacity_;
  }

  const PvsFile* file_;
  std::unique_ptr<std::uint32_t[]> buffer_;  ///< slots_ slots of capacity_ entries
  std::size_t capacity_ = 0;                 ///< decode_buffer_size()
  std::size_t slots_ = 0;
  std::size_t ways_ = 1;  ///< slots per set; set s is slots [s * ways_, (s + 1) * ways_)
  /// Per slot: its cell (kNoCell when empty), its list's size and when it was last used.
  std::unique_ptr<std::uint32_t[]> slot_cell_;
  std::unique_ptr<std::uint32_t[]> slot_size_;
  std::unique_ptr<std::uint64_t[]> slot_used_;
  std::uint64_t tick_ = 0;
  std::uint32_t decoded_cell_ = kNoCell;  ///< the cell view() holds after decode(), else none
  const std::uint32_t* result_ = nullptr;
  std::size_t size_ = 0;
  // Storage of unions and deltas (allocated on first use) and the union's marks, one bit per
  // object, all zero between calls.
  std::unique_ptr<std::uint32_t[]> sets_;
  std::size_t sets_capacity_ = 0;
  std::unique_ptr<std::uint32_t[]> marks_;
  IndexSpan entered_{}, left_{};
};

}  // namespace urbanpvs::runtime
