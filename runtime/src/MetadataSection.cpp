// SPDX-License-Identifier: MIT
// The metadata section: frame, bake settings, free-form properties (FORMAT.md, "metadata").
#include <cmath>

#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"
#include "Utf8.hpp"

namespace urbanpvs::runtime::detail {
namespace {

constexpr std::uint32_t kFlagGeographic = 1u;

bool read_string(ByteReader& r, std::string_view& out) noexcept {
  const unsigned char* data;
  std::uint32_t length;
  if (!r.string(data, length) || !is_valid_utf8(data, length)) return false;
  out = std::string_view(reinterpret_cast<const char*>(data), length);
  return true;
}

bool read_finite(ByteReader& r, double& v) noexcept {
  return r.f64(v) && std::isfinite(v);
}

}  // namespace

std::vector<unsigned char> write_metadata(const Metadata& meta) {
  ByteWriter w;
  const Frame& f = meta.frame;
  w.u32(f.geographic ? kFlagGeographic : 0u);
  w.string(f.crs);
  w.f64(f.geodetic_origin.lat_deg);
  w.f64(f.geodetic_origin.lon_deg);
  w.f64(f.geodetic_origin.h_m);
  for (double v : f.origin) w.f64(v);
  const BakeSettings& s = meta.settings;
  for (double v : {s.epsilon_m, s.pixel_size_m, s.max_cell_edge_m, s.eye_min_m, s.eye_max_m}) {
    w.f64(v);
  }
  w.u64(s.input_hash);
  w.u32(static_cast<std::uint32_t>(meta.properties.size()));
  for (const auto& [key, value] : meta.properties) {
    w.string(key);
    w.string(value);
  }
  return std::move(w.bytes());
}

bool read_metadata(const SectionBytesView& in, MetadataView& out, const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint32_t flags;
  FrameInfo& f = out.frame;
  BakeSettings& s = out.settings;
  if (!r.u32(flags) || (!in.allow_extension && (flags & ~kFlagGeographic) != 0)) {
    detail = "metadata: bad flags";
    return false;
  }
  f.geographic = (flags & kFlagGeographic) != 0;
  if (!read_string(r, f.crs)) {
    detail = "metadata: bad CRS string";
    return false;
  }
  if (!read_finite(r, f.geodetic_origin.lat_deg) || !read_finite(r, f.geodetic_origin.lon_deg) ||
      !read_finite(r, f.geodetic_origin.h_m) || std::fabs(f.geodetic_origin.lat_deg) > 90 ||
      !read_finite(r, f.origin[0]) || !read_finite(r, f.origin[1]) ||
      !read_finite(r, f.origin[2])) {
    detail = "metadata: bad frame origin";
    return false;
  }
  if (!read_finite(r, s.epsilon_m) || !read_finite(r, s.pixel_size_m) ||
      !read_finite(r, s.max_cell_edge_m) || !read_finite(r, s.eye_min_m) ||
      !read_finite(r, s.eye_max_m) || !r.u64(s.input_hash)) {
    detail = "metadata: bad bake settings";
    return false;
  }
  std::uint32_t count;
  // Each property takes at least 8 bytes: bound the reservation by what the section can hold.
  if (!r.u32(count) || count > r.remaining() / 8) {
    detail = "metadata: bad property count";
    return false;
  }
  out.properties.clear();
  out.properties.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    std::string_view key, value;
    if (!read_string(r, key) || !read_string(r, value)) {
      detail = "metadata: bad property string";
      return false;
    }
    out.properties.emplace_back(key, value);
  }
  if (r.remaining() != 0 && !in.allow_extension) {
    detail = "metadata: unexpected bytes at the end";
    return false;
  }
  return true;
}

}  // namespace urbanpvs::runtime::detail
