// SPDX-License-Identifier: MIT
// The C API: each function forwards to PvsFile after checking its pointers.
#include <new>

#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/urbanpvs.h"

using urbanpvs::runtime::CellGeometry;
using urbanpvs::runtime::IndexSpan;
using urbanpvs::runtime::LoadOptions;
using urbanpvs::runtime::ObjectInfo;
using urbanpvs::runtime::PvsDecoder;
using urbanpvs::runtime::PvsFile;
using urbanpvs::runtime::Status;

struct urbanpvs_file {
  PvsFile file;
};

struct urbanpvs_decoder {
  urbanpvs_decoder(const PvsFile& f, std::size_t cached_cells) noexcept
      : decoder(f, cached_cells) {}
  PvsDecoder decoder;
};

namespace {

#define URBANPVS_SAME(c, cpp) \
  static_assert(static_cast<int>(c) == static_cast<int>(Status::cpp), #c " differs from " #cpp)
URBANPVS_SAME(URBANPVS_OK, kOk);
URBANPVS_SAME(URBANPVS_BAD_MAGIC, kBadMagic);
URBANPVS_SAME(URBANPVS_UNSUPPORTED_VERSION, kUnsupportedVersion);
URBANPVS_SAME(URBANPVS_UNSUPPORTED_FEATURE, kUnsupportedFeature);
URBANPVS_SAME(URBANPVS_TRUNCATED, kTruncated);
URBANPVS_SAME(URBANPVS_TRAILING_BYTES, kTrailingBytes);
URBANPVS_SAME(URBANPVS_HEADER_CHECKSUM_MISMATCH, kHeaderChecksumMismatch);
URBANPVS_SAME(URBANPVS_SECTION_CHECKSUM_MISMATCH, kSectionChecksumMismatch);
URBANPVS_SAME(URBANPVS_MALFORMED_HEADER, kMalformedHeader);
URBANPVS_SAME(URBANPVS_MISSING_SECTION, kMissingSection);
URBANPVS_SAME(URBANPVS_MALFORMED_SECTION, kMalformedSection);
URBANPVS_SAME(URBANPVS_OUT_OF_RANGE, kOutOfRange);
URBANPVS_SAME(URBANPVS_BUFFER_TOO_SMALL, kBufferTooSmall);
URBANPVS_SAME(URBANPVS_OUT_OF_MEMORY, kOutOfMemory);
URBANPVS_SAME(URBANPVS_IO_ERROR, kIoError);
URBANPVS_SAME(URBANPVS_NOT_GEOGRAPHIC, kNotGeographic);
URBANPVS_SAME(URBANPVS_INVALID_ARGUMENT, kInvalidArgument);
URBANPVS_SAME(URBANPVS_NOT_EXPANDED, kNotExpanded);
#undef URBANPVS_SAME
static_assert(URBANPVS_NO_CELL == urbanpvs::runtime::kNoCell, "URBANPVS_NO_CELL differs");

urbanpvs_status to_c(Status s) noexcept {
  return static_cast<urbanpvs_status>(s);
}

template <class Open>
urbanpvs_status open_with(urbanpvs_file** out, Open open) noexcept {
  if (out == nullptr) return URBANPVS_INVALID_ARGUMENT;
  *out = nullptr;
  urbanpvs_file* handle = new (std::nothrow) urbanpvs_file;
  if (handle == nullptr) return URBANPVS_OUT_OF_MEMORY;
  const Status status = open(handle->file);
  if (status != Status::kOk) {
    delete handle;
    return to_c(status);
  }
  *out = handle;
  return URBANPVS_OK;
}

}  // namespace

extern "C" {

const char* urbanpvs_status_message(urbanpvs_status status) {
  return urbanpvs::runtime::status_message(static_cast<Status>(status));
}

urbanpvs_status urbanpvs_open_memory(const void* data, size_t size, urbanpvs_file** out) {
  return open_with(out, [&](PvsFile& f) { return PvsFile::open(data, size, f); });
}

urbanpvs_status urbanpvs_open_file(const char* path, urbanpvs_file** out) {
  if (path == nullptr) return URBANPVS_INVALID_ARGUMENT;
  return open_with(out, [&](PvsFile& f) { return PvsFile::open_file(path, f); });
}

urbanpvs_status urbanpvs_open_file_flags(const char* path, uint32_t flags, urbanpvs_file** out) {
  if (path == nullptr || (flags & ~URBANPVS_OPEN_EXPAND_PVS) != 0) {
    if (out != nullptr) *out = nullptr;
    return URBANPVS_INVALID_ARGUMENT;
  }
  LoadOptions options;
  options.expand_pvs = (flags & URBANPVS_OPEN_EXPAND_PVS) != 0;
  return open_with(out, [&](PvsFile& f) { return PvsFile::open_file(path, f, options); });
}

void urbanpvs_close(urbanpvs_file* file) {
  delete file;
}

uint32_t urbanpvs_object_count(const urbanpvs_file* file) {
  return file != nullptr ? file->file.object_count() : 0;
}

uint32_t urbanpvs_cell_count(const urbanpvs_file* file) {
  return file != nullptr ? file->file.cell_count() : 0;
}

uint32_t urbanpvs_locate(const urbanpvs_file* file, double x, double y, double z) {
  return file != nullptr ? file->file.locate(x, y, z) : URBANPVS_NO_CELL;
}

uint32_t urbanpvs_locate_from(const urbanpvs_file* file, uint32_t hint, double x, double y,
                              double z) {
  return file != nullptr ? file->file.locate_from(hint, x, y, z) : URBANPVS_NO_CELL;
}

urbanpvs_status urbanpvs_input_to_local(const urbanpvs_file* file, double xyz[3]) {
  if (file == nullptr || xyz == nullptr) return URBANPVS_INVALID_ARGUMENT;
  const auto local = file->file.input_to_local(xyz[0], xyz[1], xyz[2]);
  for (int i = 0; i < 3; ++i) xyz[i] = local[i];
  return URBANPVS_OK;
}

urbanpvs_status urbanpvs_geodetic_to_local(const urbanpvs_file* file, double lat_deg,
                                           double lon_deg, double h_m, double local_xyz[3]) {
  if (file == nullptr || local_xyz == nullptr) return URBANPVS_INVALID_ARGUMENT;
  std::array<double, 3> local{};
  const Status status = file->file.geodetic_to_local(lat_deg, lon_deg, h_m, local);
  if (status == Status::kOk) {
    for (int i = 0; i < 3; ++i) local_xyz[i] = local[i];
  }
  return to_c(status);
}

uint32_t urbanpvs_pvs_size(const urbanpvs_file* file, uint32_t cell) {
  return file != nullptr ? file->file.pvs_size(cell) : 0;
}

size_t urbanpvs_decode_buffer_size(const urbanpvs_file* file) {
  return file != nullptr ? file->file.decode_buffer_size() : 0;
}

urbanpvs_status urbanpvs_pvs(const urbanpvs_file* file, uint32_t cell, uint32_t* buffer,
                             size_t capacity, size_t* count) {
  if (file == nullptr || buffer == nullptr || count == nullptr) return URBANPVS_INVALID_ARGUMENT;
  return to_c(file->file.decode_pvs(cell, buffer, capacity, *count));
}

int urbanpvs_is_visible(const urbanpvs_file* file, uint32_t cell, uint32_t object) {
  return file != nullptr && file->file.is_visible(cell, object) ? 1 : 0;
}

urbanpvs_status urbanpvs_pvs_span(const urbanpvs_file* file, uint32_t cell, const uint32_t** data,
                                  size_t* count) {
  if (file == nullptr || data == nullptr || count == nullptr) return URBANPVS_INVALID_ARGUMENT;
  IndexSpan span;
  const Status status = file->file.pvs_span(cell, span);
  if (status != Status::kOk) return to_c(status);
  *data = span.data;
  *count = span.size;
  return URBANPVS_OK;
}

urbanpvs_status urbanpvs_object(const urbanpvs_file* file, uint32_t object, const char** id,
                                size_t* id_size, double bbox[6]) {
  if (file == nullptr) return URBANPVS_INVALID_ARGUMENT;
  ObjectInfo info;
  const Status status = file->file.object(object, info);
  if (status != Status::kOk) return to_c(status);
  if (id != nullptr) *id = info.source_id.data();
  if (id_size != nullptr) *id_size = info.source_id.size();
  if (bbox != nullptr) {
    for (int i = 0; i < 6; ++i) bbox[i] = info.bbox[i];
  }
  return URBANPVS_OK;
}

urbanpvs_status urbanpvs_object_payload(const urbanpvs_file* file, uint32_t object,
                                        const char** payload, size_t* size) {
  if (file == nullptr || payload == nullptr || size == nullptr) return URBANPVS_INVALID_ARGUMENT;
  ObjectInfo info;
  const Status status = file->file.object(object, info);
  if (status != Status::kOk) return to_c(status);
  *payload = info.payload.data();
  *size = info.payload.size();
  return URBANPVS_OK;
}

void urbanpvs_payload_key(const urbanpvs_file* file, const char** key, size_t* size) {
  const std::string_view k = file != nullptr ? file->file.payload_key() : std::string_view{};
  if (key != nullptr) *key = k.data();
  if (size != nullptr) *size = k.size();
}

urbanpvs_status urbanpvs_cell(const urbanpvs_file* file, uint32_t cell, double triangle[6],
                              double z_range[2], uint32_t neighbours[3]) {
  if (file == nullptr) return URBANPVS_INVALID_ARGUMENT;
  CellGeometry c;
  const Status status = file->file.cell(cell, c);
  if (status != Status::kOk) return to_c(status);
  for (int i = 0; i < 3; ++i) {
    if (triangle != nullptr) {
      triangle[2 * i] = c.triangle[i].x;
      triangle[2 * i + 1] = c.triangle[i].y;
    }
    if (neighbours != nullptr) neighbours[i] = c.neighbours[i];
  }
  if (z_range != nullptr) {
    z_range[0] = c.z_min;
    z_range[1] = c.z_max;
  }
  return URBANPVS_OK;
}

urbanpvs_status urbanpvs_decoder_create(const urbanpvs_file* file, urbanpvs_decoder** out) {
  return urbanpvs_decoder_create_cached(file, 1, out);
}

urbanpvs_status urbanpvs_decoder_create_cached(const urbanpvs_file* file, size_t cached_cells,
                                               urbanpvs_decoder** out) {
  if (out == nullptr) return URBANPVS_INVALID_ARGUMENT;
  *out = nullptr;
  if (file == nullptr) return URBANPVS_INVALID_ARGUMENT;
  urbanpvs_decoder* decoder = new (std::nothrow) urbanpvs_decoder(file->file, cached_cells);
  // The C++ decoder falls back to one slot when the cache does not fit; here that is a failure.
  if (decoder == nullptr || decoder->decoder.cached_cells() < cached_cells) {
    delete decoder;
    return URBANPVS_OUT_OF_MEMORY;
  }
  *out = decoder;
  return URBANPVS_OK;
}

void urbanpvs_decoder_destroy(urbanpvs_decoder* decoder) {
  delete decoder;
}

urbanpvs_status urbanpvs_decoder_pvs(urbanpvs_decoder* decoder, uint32_t cell,
                                     const uint32_t** objects, size_t* count) {
  if (decoder == nullptr || objects == nullptr || count == nullptr)
    return URBANPVS_INVALID_ARGUMENT;
  const Status status = decoder->decoder.decode(cell);
  *objects = decoder->decoder.begin();
  *count = decoder->decoder.size();
  return to_c(status);
}

urbanpvs_status urbanpvs_pvs_union(urbanpvs_decoder* decoder, const uint32_t* cells, size_t n,
                                   const uint32_t** objects, size_t* count) {
  if (decoder == nullptr || objects == nullptr || count == nullptr)
    return URBANPVS_INVALID_ARGUMENT;
  const Status status = decoder->decoder.decode_union(cells, n);
  *objects = decoder->decoder.begin();
  *count = decoder->decoder.size();
  return to_c(status);
}

urbanpvs_status urbanpvs_pvs_delta(urbanpvs_decoder* decoder, uint32_t from, uint32_t to,
                                   const uint32_t** entered, size_t* entered_count,
                                   const uint32_t** left, size_t* left_count) {
  if (decoder == nullptr || entered == nullptr || entered_count == nullptr || left == nullptr ||
      left_count == nullptr)
    return URBANPVS_INVALID_ARGUMENT;
  const Status status = decoder->decoder.decode_delta(from, to);
  *entered = decoder->decoder.entered().data;
  *entered_count = decoder->decoder.entered().size;
  *left = decoder->decoder.left().data;
  *left_count = decoder->decoder.left().size;
  return to_c(status);
}

}  // extern "C"
