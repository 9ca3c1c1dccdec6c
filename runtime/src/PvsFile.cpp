// SPDX-License-Identifier: MIT
// PvsFile and PvsDecoder: the query side. Everything here reads views that load() validated.
#include "urbanpvs/runtime/PvsFile.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>
#include <utility>

#include "Bits.hpp"
#include "ByteReader.hpp"
#include "PvsFileData.hpp"
#include "urbanpvs/runtime/FileIo.hpp"

namespace urbanpvs::runtime {
namespace {

/// Whether the cell `shape` holds (x, y) and, when `check_z`, z.
bool holds(const detail::CellShape& shape, double x, double y, double z, bool check_z) noexcept {
  if (check_z && !(z >= shape.z_min && z <= shape.z_max)) return false;
  return triangle_contains(shape.triangle, x, y);
}

/// locate() from a bucket of an expanded file: the candidates' records hold their shapes and
/// the start of their PVSs, so one round of fetches serves the tests and the decode after them.
std::uint32_t locate_in_records(const detail::PvsFileData& f, const detail::GridBucket& b,
                                const detail::BucketRecords& in, double x, double y, double z,
                                bool check_z) noexcept {
  const std::uint32_t* const records = f.expanded.ids.data();
  constexpr std::size_t kRecord = detail::PvsExpansion::kRecordWords;
  for (std::uint32_t k = 0; k < b.count; ++k) {
    const std::uint32_t* r = records + std::size_t{in.record[k]} * kRecord;
    URBANPVS_PREFETCH(r);
    URBANPVS_PREFETCH(r + kRecord);  // the header and the first ids
    URBANPVS_PREFETCH(&f.expanded.offsets[b.cell[k]]);
  }
  for (std::uint32_t k = 0; k < b.count; ++k) {
    detail::CellShape shape;  // copied out of the record, where the loader copied it in
    std::memcpy(static_cast<void*>(&shape), records + std::size_t{in.record[k]} * kRecord,
                sizeof shape);
    if (holds(shape, x, y, z, check_z)) return b.cell[k];
  }
  return kNoCell;
}

/// The first (lowest-index) cell of (x, y)'s grid list whose triangle contains the point and,
/// when `check_z`, whose z range contains z. Lists are ascending and the grid lists every cell
/// whose box covers the grid cell, so this is the lowest-index containing cell overall.
std::uint32_t locate_in(const detail::PvsFileData& f, double x, double y, double z,
                        bool check_z) noexcept {
  if (!std::isfinite(x) || !std::isfinite(y) || (check_z && std::isnan(z))) return kNoCell;
  const detail::GridGeometry& g = f.grid.geometry;
  const std::size_t grid_cell =
      std::size_t{detail::grid_coordinate(y, g.origin_y, g.size_y, g.ny)} * g.nx +
      detail::grid_coordinate(x, g.origin_x, g.size_x, g.nx);
  // The grid cell's list, inline in its bucket when it fits, else in the grid's entries.
  const std::uint32_t* e = nullptr;
  const std::uint32_t* end = nullptr;
  const detail::LocateIndex& index = f.locate;
  if (!index.buckets.empty() && index.buckets[grid_cell].count <= detail::GridBucket::kCapacity) {
    const detail::GridBucket& b = index.buckets[grid_cell];
    if (!index.records.empty())
      return locate_in_records(f, b, index.records[grid_cell], x, y, z, check_z);
    e = b.cell;
    end = b.cell + b.count;
  } else {
    e = f.grid.entries.data() + f.grid.offsets[grid_cell];
    end = f.grid.entries.data() + f.grid.offsets[grid_cell + 1];
  }
  // The candidates are scattered over the cell table: ask for all of them at once, so their
  // cache misses overlap instead of following one another (random queries are memory bound).
  // Where each one's PVS starts is asked for too: the decode that usually follows needs it
  // first, and would otherwise wait one more miss after the shape tests.
  for (const std::uint32_t* p = e; p != end; ++p) {
    URBANPVS_PREFETCH(&f.cells.shapes[*p]);
    if (f.expanded.empty()) {
      detail::prefetch_pvs_start(f.pvs.section, *p);
    } else {
      URBANPVS_PREFETCH(&f.expanded.offsets[*p]);
    }
  }
  for (; e != end; ++e)
    if (holds(f.cells.shapes[*e], x, y, z, check_z)) return *e;
  return kNoCell;
}

/// A new PvsFileData for `out`; null (with out closed and `error` set) when memory is short.
std::unique_ptr<detail::PvsFileData> new_file_data(PvsFile& out, LoadError* error) noexcept {
  std::unique_ptr<detail::PvsFileData> file(new (std::nothrow) detail::PvsFileData);
  if (!file) {
    out = PvsFile();
    if (error != nullptr) *error = {Status::kOutOfMemory, 0, "out of memory while loading"};
  }
  return file;
}

}  // namespace

PvsFile::PvsFile() noexcept = default;
PvsFile::~PvsFile() = default;
PvsFile::PvsFile(PvsFile&& other) noexcept = default;
PvsFile& PvsFile::operator=(PvsFile&& other) noexcept = default;

Status PvsFile::open_data(std::unique_ptr<detail::PvsFileData> data, PvsFile& out,
                          const LoadOptions& options, LoadError* error) noexcept {
  LoadError local;
  const Status status = detail::load(*data, options, error != nullptr ? *error : local);
  out.data_.reset();
  if (status == Status::kOk) out.data_ = std::move(data);
  return status;
}

Status PvsFile::open(const void* data, std::size_t size, PvsFile& out, const LoadOptions& options,
                     LoadError* error) noexcept {
  if (data == nullptr && size != 0) {
    out.data_.reset();
    if (error != nullptr) *error = {Status::kInvalidArgument, 0, "null buffer"};
    return Status::kInvalidArgument;
  }
  std::unique_ptr<detail::PvsFileData> file = new_file_data(out, error);
  if (!file) return Status::kOutOfMemory;
  file->data = static_cast<const unsigned char*>(data);
  file->size = size;
  return open_data(std::move(file), out, options, error);
}

Status PvsFile::open_owned(std::vector<std::byte>&& bytes, PvsFile& out, const LoadOptions& options,
                           LoadError* error) noexcept {
  std::vector<std::byte> owned = std::move(bytes);
  std::unique_ptr<detail::PvsFileData> file = new_file_data(out, error);
  if (!file) return Status::kOutOfMemory;
  file->owned = std::move(owned);  // a vector move keeps the data pointer
  file->data = reinterpret_cast<const unsigned char*>(file->owned.data());
  file->size = file->owned.size();
  return open_data(std::move(file), out, options, error);
}

Status PvsFile::open_file(const char* path, PvsFile& out, const LoadOptions& options,
                          LoadError* error) noexcept {
  std::unique_ptr<detail::PvsFileData> file = new_file_data(out, error);
  if (!file) return Status::kOutOfMemory;
  const Status status = detail::read_file_large(path, file->read);
  if (status != Status::kOk) {
    out.data_.reset();
    if (error != nullptr) *error = {status, 0, "cannot read the file"};
    return status;
  }
  file->data = reinterpret_cast<const unsigned char*>(file->read.data());
  file->size = file->read.size();
  return open_data(std::move(file), out, options, error);
}

bool PvsFile::is_open() const noexcept {
  return data_ != nullptr;
}
std::uint16_t PvsFile::major_version() const noexcept {
  return data_ ? data_->container.major : 0;
}
std::uint16_t PvsFile::minor_version() const noexcept {
  return data_ ? data_->container.minor : 0;
}
std::size_t PvsFile::file_size() const noexcept {
  return data_ ? data_->size : 0;
}

std::size_t PvsFile::section_count() const noexcept {
  return data_ ? data_->container.sections.size() : 0;
}

SectionInfo PvsFile::section(std::size_t index) const noexcept {
  if (!data_ || index >= data_->container.sections.size()) return {};
  return data_->container.sections[index];
}

FrameInfo PvsFile::frame() const noexcept {
  return data_ ? data_->metadata.frame : FrameInfo{};
}
BakeSettings PvsFile::settings() const noexcept {
  return data_ ? data_->metadata.settings : BakeSettings{};
}

std::size_t PvsFile::property_count() const noexcept {
  return data_ ? data_->metadata.properties.size() : 0;
}

Status PvsFile::property(std::size_t index, std::string_view& key,
                         std::string_view& value) const noexcept {
  if (index >= property_count()) return Status::kOutOfRange;
  key = data_->metadata.properties[index].first;
  value = data_->metadata.properties[index].second;
  return Status::kOk;
}

std::array<double, 3> PvsFile::input_to_local(double x, double y, double z) const noexcept {
  const std::array<double, 3> o = frame().origin;
  return {x - o[0], y - o[1], z - o[2]};
}

std::array<double, 3> PvsFile::local_to_input(double x, double y, double z) const noexcept {
  const std::array<double, 3> o = frame().origin;
  return {x + o[0], y + o[1], z + o[2]};
}

Status PvsFile::geodetic_to_local(double lat_deg, double lon_deg, double h_m,
                                  std::array<double, 3>& local) const noexcept {
  if (!data_ || !data_->metadata.frame.geographic) return Status::kNotGeographic;
  // As the preprocessor maps its input: east and north of the point's foot on the ellipsoid,
  // and the height as given, so that verticals stay vertical in the flat local frame.
  const std::array<double, 3> enu = data_->geodetic_frame.forward(lat_deg, lon_deg, 0);
  local = input_to_local(enu[0], enu[1], h_m);
  return Status::kOk;
}

std::uint32_t PvsFile::object_count() const noexcept {
  return data_ ? data_->objects.count : 0;
}
std::uint32_t PvsFile::cell_count() const noexcept {
  return data_ ? data_->cells.count : 0;
}

Status PvsFile::object(std::uint32_t index, ObjectInfo& out) const noexcept {
  if (index >= object_count()) return Status::kOutOfRange;
  out = detail::object_at(data_->objects, index);
  out.payload = detail::payload_at(data_->payloads, index);
  return Status::kOk;
}

bool PvsFile::has_payloads() const noexcept {
  return data_ && data_->payloads.present;
}
std::string_view PvsFile::payload_key() const noexcept {
  return data_ ? data_->payloads.key : std::string_view{};
}

Status PvsFile::cell(std::uint32_t index, CellGeometry& out) const noexcept {
  if (index >= cell_count()) return Status::kOutOfRange;
  out = detail::cell_at(data_->cells, index);
  return Status::kOk;
}

std::uint32_t PvsFile::locate(double x, double y, double z) const noexcept {
  return data_ ? locate_in(*data_, x, y, z, true) : kNoCell;
}

std::uint32_t PvsFile::locate_xy(double x, double y) const noexcept {
  return data_ ? locate_in(*data_, x, y, 0, false) : kNoCell;
}

std::uint32_t PvsFile::locate_from(std::uint32_t hint, double x, double y,
                                   double z) const noexcept {
  if (!data_) return kNoCell;
  const detail::PvsFileData& f = *data_;
  // holds() rejects NaN z by its range test, and a non-finite x or y by the triangle's box.
  if (hint < f.cells.count) {
    if (holds(f.cells.shapes[hint], x, y, z, true)) return hint;
    for (const std::uint32_t n : f.cells.neighbours[hint])
      if (n < f.cells.count && holds(f.cells.shapes[n], x, y, z, true)) return n;
  }
  return locate_in(f, x, y, z, true);
}

std::uint32_t PvsFile::pvs_size(std::uint32_t cell) const noexcept {
  if (IndexSpan span; pvs_span(cell, span) == Status::kOk)
    return static_cast<std::uint32_t>(span.size);
  // A coded diff's size is derived along its chain (FORMAT.md, "5 — pvs, coded").
  detail::Chain chain;
  if (!data_ || !detail::resolve_chain(data_->pvs.section, cell, chain)) return 0;
  return chain.headers[0].count;
}

std::uint32_t PvsFile::max_pvs_size() const noexcept {
  return data_ ? data_->pvs.max_pvs_size : 0;
}
std::uint64_t PvsFile::total_pvs_entries() const noexcept {
  return data_ ? data_->pvs.total_entries : 0;
}
std::size_t PvsFile::decode_buffer_size() const noexcept {
  return data_ ? data_->decode_buffer_size : 0;
}

bool PvsFile::is_expanded() const noexcept {
  return data_ && !data_->expanded.empty();
}

Status PvsFile::pvs_span(std::uint32_t cell, IndexSpan& out) const noexcept {
  if (cell >= cell_count()) return Status::kOutOfRange;
  if (!is_expanded()) return Status::kNotExpanded;
  const detail::PvsExpansion& x = data_->expanded;
  out = {x.ids.data() + x.offsets[cell], x.size(cell)};
  return Status::kOk;
}

Status PvsFile::decode_pvs(std::uint32_t cell, std::uint32_t* buffer, std::size_t capacity,
                           std::size_t& count) const noexcept {
  if (cell >= cell_count()) return Status::kOutOfRange;
  if (buffer == nullptr) return Status::kInvalidArgument;
  if (capacity < data_->decode_buffer_size) return Status::kBufferTooSmall;
  if (IndexSpan span; pvs_span(cell, span) == Status::kOk) {
    std::copy(span.begin(), span.end(), buffer);
    count = span.size;
    return Status::kOk;
  }
  const std::size_t half = std::max<std::size_t>(data_->pvs.max_pvs_size, 1);
  return detail::decode_cell(data_->pvs.section, cell, buffer, half, count);
}

bool PvsFile::is_visible(std::uint32_t cell, std::uint32_t object) const noexcept {
  if (cell >= cell_count() || object >= object_count()) return false;
  if (IndexSpan span; pvs_span(cell, span) == Status::kOk) {
    return std::binary_search(span.begin(), span.end(), object);
  }
  return detail::cell_contains(data_->pvs.section, cell, object);
}

Status PvsFile::pvs_encoding(std::uint32_t cell, PvsEncodingInfo& out) const noexcept {
  if (cell >= cell_count()) return Status::kOutOfRange;
  detail::Chain chain;
  if (!detail::resolve_chain(data_->pvs.section, cell, chain)) return Status::kMalformedSection;
  const detail::PayloadHeader& h = chain.headers[0];
  out.kind = static_cast<std::uint8_t>(h.kind);
  out.reference = chain.diff_steps > 0 ? chain.diffs[0].reference : kNoCell;
  out.chain_length = chain.diff_steps;
  std::uint32_t begin = 0, end = 0;
  if (!detail::payload_range(data_->pvs.section, cell, begin, end)) {
    return Status::kMalformedSection;
  }
  out.payload_bytes = end - begin;
  return Status::kOk;
}

namespace {

/// Slots per set of the decoder's cache. A crowd's cells map to sets by hash; with few ways,
/// more agents than ways land in some sets and evict each other on every turn (200 walkers in
/// 64 sets of 4: a quarter of the queries missed). 16 ids are one cache line to scan.
constexpr std::size_t kWays = 16;

/// The set of `cell` among `sets` (Fibonacci hashing: neighbouring cell indices, which a walker
/// visits in turn, land in different sets).
std::size_t set_of(std::uint32_t cell, std::size_t sets) noexcept {
  return static_cast<std::size_t>((std::uint64_t{cell} * 0x9E3779B97F4A7C15ull) >> 32) % sets;
}

}  // namespace

PvsDecoder::PvsDecoder(const PvsFile& file, std::size_t cached_cells) noexcept
    : file_(&file), capacity_(file.decode_buffer_size()) {
  // Whole sets of kWays when there are more than kWays slots; one set of them all otherwise.
  std::size_t wanted = std::max<std::size_t>(cached_cells, 1);
  if (wanted > kWays && wanted <= SIZE_MAX - kWays) wanted = (wanted + kWays - 1) / kWays * kWays;
  const std::size_t slot = std::max<std::size_t>(capacity_, 1);
  for (std::size_t n : {wanted, std::size_t{1}}) {
    if (n > SIZE_MAX / slot / sizeof(std::uint32_t)) continue;
    buffer_.reset(new (std::nothrow) std::uint32_t[n * slot]);
    slot_cell_.reset(new (std::nothrow) std::uint32_t[n]);
    slot_size_.reset(new (std::nothrow) std::uint32_t[n]);
    slot_used_.reset(new (std::nothrow) std::uint64_t[n]);
    if (buffer_ && slot_cell_ && slot_size_ && slot_used_) {
      slots_ = n;
      break;
    }
  }
  if (slots_ == 0) {
    buffer_.reset();
    capacity_ = 0;
    return;
  }
  capacity_ = slot;
  ways_ = std::min(slots_, kWays);
  std::fill(slot_cell_.get(), slot_cell_.get() + slots_, kNoCell);
  std::fill(slot_size_.get(), slot_size_.get() + slots_, 0u);
  std::fill(slot_used_.get(), slot_used_.get() + slots_, std::uint64_t{0});
  result_ = buffer_.get();
}

PvsDecoder::~PvsDecoder() = default;

void PvsDecoder::clear() noexcept {
  result_ = buffer_.get();
  size_ = 0;
  entered_ = left_ = IndexSpan{};
  decoded_cell_ = kNoCell;
}

std::size_t PvsDecoder::set_start(std::uint32_t cell) const noexcept {
  return set_of(cell, slots_ / ways_) * ways_;
}

std::size_t PvsDecoder::find_slot(std::uint32_t cell) const noexcept {
  if (slots_ == 0 || cell == kNoCell) return slots_;
  const std::size_t first = set_start(cell);
  for (std::size_t k = first; k < first + ways_; ++k)
    if (slot_cell_[k] == cell) return k;
  return slots_;
}

Status PvsDecoder::fetch(std::uint32_t cell, IndexSpan& out) noexcept {
  if (file_->pvs_span(cell, out) == Status::kOk) return Status::kOk;
  if (cell >= file_->cell_count()) return Status::kOutOfRange;
  if (slots_ == 0) return Status::kOutOfMemory;
  if (const std::size_t hit = find_slot(cell); hit != slots_) {
    slot_used_[hit] = ++tick_;
    out = {slot_data(hit), slot_size_[hit]};
    return Status::kOk;
  }
  // A diff whose reference is cached (in another slot of the cache) is one merge against it.
  const detail::PvsSection& section = file_->data_->pvs.section;
  detail::PayloadHeader header;
  detail::DiffHeader diff;
  std::size_t reference = slots_;
  if (slots_ > 1 && detail::read_payload_header(section, cell, header) &&
      header.kind == format::PvsKind::kDiff &&
      detail::read_diff_header(section, cell, header, diff))
    reference = find_slot(diff.reference);
  // The least recently used slot of the cell's set, but not the reference's, which is read
  // while the new list is written (with two or more slots, a set has two or more).
  const std::size_t first = set_start(cell);
  std::size_t victim = slots_;
  for (std::size_t k = first; k < first + ways_; ++k)
    if (k != reference && (victim == slots_ || slot_used_[k] < slot_used_[victim])) victim = k;
  slot_cell_[victim] = kNoCell;
  std::uint32_t* const list = slot_data(victim);
  std::size_t count = 0;
  if (reference != slots_) {
    // load() checked that every diff merges cleanly with its reference's list.
    if (!detail::merge_decoded(diff, slot_data(reference), slot_size_[reference], list, capacity_,
                               count)) {
      return Status::kMalformedSection;
    }
    slot_used_[reference] = ++tick_;
  } else if (const Status status = file_->decode_pvs(cell, list, capacity_, count);
             status != Status::kOk) {
    return status;
  }
  slot_cell_[victim] = cell;
  slot_size_[victim] = static_cast<std::uint32_t>(count);
  slot_used_[victim] = ++tick_;
  out = {list, count};
  return Status::kOk;
}

Status PvsDecoder::decode(std::uint32_t cell) noexcept {
  // A camera stays in its cell for many frames: the same cell again costs nothing.
  if (cell == decoded_cell_ && cell != kNoCell) return Status::kOk;
  IndexSpan span;
  const Status status = fetch(cell, span);
  clear();
  if (status != Status::kOk) return status;
  if (file_->is_expanded()) {
    // Expanded file: no copy. A new cell's list is asked for all at once, not line by line as
    // the caller reads it: on a random query that is one wait instead of a stream of them
    // (Monaco's 1,142 entries per cell: random p50 1.1 -> 0.7 µs).
    const auto* line = reinterpret_cast<const unsigned char*>(span.data);
    for (std::size_t b = 0; b < span.size * sizeof(std::uint32_t); b += 64)
      URBANPVS_PREFETCH(line + b);
  }
  result_ = span.data;
  size_ = span.size;
  decoded_cell_ = cell;
  return Status::kOk;
}

}  // namespace urbanpvs::runtime
