// SPDX-License-Identifier: MIT
// The objects section: fixed-size records (source id reference + bounding box) followed by the
// concatenated source ids (FORMAT.md, "objects"). Fixed records make object(i) O(1).
#include <cmath>
#include <limits>
#include <string>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"
#include "Utf8.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::size_t kHeaderSize = 16;  // count u32, width u8, 3 zero bytes, strings size u64

/// Largest float <= v and smallest float >= v: float32 boxes are rounded outwards so they only
/// ever grow (conservative for culling).
float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

double read_coordinate(const unsigned char* p, std::uint8_t width) noexcept {
  return width == format::kBboxFloat32 ? static_cast<double>(load_f32(p)) : load_f64(p);
}

}  // namespace

std::vector<unsigned char> write_objects(const std::vector<ObjectRecord>& objects, bool float32) {
  ByteWriter w;
  w.u32(static_cast<std::uint32_t>(objects.size()));
  w.u8(float32 ? format::kBboxFloat32 : format::kBboxFloat64);
  w.u8(0);
  w.u8(0);
  w.u8(0);
  std::uint64_t strings_size = 0;
  for (const ObjectRecord& o : objects) strings_size += o.source_id.size();
  w.u64(strings_size);
  std::uint64_t offset = 0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const ObjectRecord& o = objects[i];
    if (offset > UINT32_MAX || strings_size > UINT32_MAX) {
      throw PvsWriteError("objects: source ids exceed 4 GiB in total");
    }
    w.u32(static_cast<std::uint32_t>(offset));
    w.u32(static_cast<std::uint32_t>(o.source_id.size()));
    offset += o.source_id.size();
    for (int k = 0; k < 6; ++k) {
      if (!float32) {
        w.f64(o.bbox[k]);
        continue;
      }
      const float f = k < 3 ? round_down(o.bbox[k]) : round_up(o.bbox[k]);
      if (!std::isfinite(f)) {
        throw PvsWriteError("object " + std::to_string(i) +
                            ": bbox outside the float32 range (encode with bbox_float32 = false)");
      }
      w.f32(f);
    }
  }
  for (const ObjectRecord& o : objects) w.string_bytes(o.source_id);
  return std::move(w.bytes());
}

bool read_objects(const SectionBytesView& in, ObjectsView& out, const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint8_t width, pad[3];
  if (!r.u32(out.count) || !r.u8(width) || !r.u8(pad[0]) || !r.u8(pad[1]) || !r.u8(pad[2]) ||
      !r.u64(out.strings_size)) {
    detail = "objects: section shorter than its header";
    return false;
  }
  if ((width != format::kBboxFloat32 && width != format::kBboxFloat64) || pad[0] != 0 ||
      pad[1] != 0 || pad[2] != 0) {
    detail = "objects: bad bounding-box width";
    return false;
  }
  out.bbox_width = width;
  out.record_size = 8 + 6 * std::size_t{width};
  std::uint64_t records_size, used;
  if (!checked_mul(out.count, out.record_size, records_size) ||
      !checked_add(records_size, out.strings_size, used) || used > r.remaining() ||
      (used != r.remaining() && !in.allow_extension)) {
    detail = "objects: count or string size does not match the section length";
    return false;
  }
  out.records = in.data + kHeaderSize;
  out.strings = out.records + records_size;
  for (std::uint32_t i = 0; i < out.count; ++i) {
    const unsigned char* rec = out.records + std::size_t{i} * out.record_size;
    const std::uint64_t offset = load_u32(rec);
    const std::uint64_t length = load_u32(rec + 4);
    if (offset + length > out.strings_size ||
        !is_valid_utf8(out.strings + offset, static_cast<std::size_t>(length))) {
      detail = "objects: bad source id";
      return false;
    }
    for (int k = 0; k < 3; ++k) {
      const double lo = read_coordinate(rec + 8 + k * width, width);
      const double hi = read_coordinate(rec + 8 + (k + 3) * width, width);
      if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi) {
        detail = "objects: bad bounding box";
        return false;
      }
    }
  }
  return true;
}

ObjectInfo object_at(const ObjectsView& view, std::uint32_t index) noexcept {
  const unsigned char* rec = view.records + std::size_t{index} * view.record_size;
  ObjectInfo info;
  info.source_id = std::string_view(reinterpret_cast<const char*>(view.strings + load_u32(rec)),
                                    load_u32(rec + 4));
  for (int k = 0; k < 6; ++k)
    info.bbox[k] = read_coordinate(rec + 8 + k * view.bbox_width, view.bbox_width);
  return info;
}

}  // namespace urbanpvs::runtime::detail
