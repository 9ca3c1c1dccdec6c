// SPDX-License-Identifier: MIT
// The payloads section (2.1, FORMAT.md "6 — payloads"): one optional UTF-8 value per object
// that the user asked the preprocessor to carry (a mesh or tile key from a CityJSON attribute or
// an OSM tag), so a renderer can go from a PVS entry to its asset without the city file. Fixed
// u32 offsets keep object_payload(i) O(1) with no allocation at load.
#include "ByteReader.hpp"
#include "ByteWriter.hpp"
#include "Sections.hpp"
#include "Utf8.hpp"

namespace urbanpvs::runtime::detail {

std::vector<unsigned char> write_payloads(const std::string& key,
                                          const std::vector<ObjectRecord>& objects) {
  ByteWriter w;
  w.u32(static_cast<std::uint32_t>(objects.size()));
  w.u32(0);
  w.string(key);
  std::uint64_t offset = 0;
  w.u32(0);
  for (const ObjectRecord& o : objects) {
    offset += o.payload.size();
    if (offset > UINT32_MAX) throw PvsWriteError("payloads: exceed 4 GiB in total");
    w.u32(static_cast<std::uint32_t>(offset));
  }
  for (const ObjectRecord& o : objects) w.string_bytes(o.payload);
  return std::move(w.bytes());
}

bool read_payloads(const SectionBytesView& in, std::uint32_t object_count, PayloadsView& out,
                   const char*& detail) {
  ByteReader r(in.data, in.size);
  std::uint32_t count, flags, key_length;
  const unsigned char* key;
  std::uint64_t offsets_size;
  if (!r.u32(count) || !r.u32(flags) || count != object_count ||
      (flags != 0 && !in.allow_extension) || !r.string(key, key_length) ||
      !is_valid_utf8(key, key_length) || !checked_mul(std::uint64_t{count} + 1, 4, offsets_size) ||
      offsets_size > r.remaining()) {
    detail = "payloads: bad header (object count, flags or key)";
    return false;
  }
  const unsigned char* offsets = nullptr;
  r.bytes(static_cast<std::size_t>(offsets_size), offsets);
  const std::uint64_t available = r.remaining();
  const std::uint64_t size = load_u32(offsets + 4 * std::size_t{count});
  if (load_u32(offsets) != 0 || size > available || (size != available && !in.allow_extension)) {
    detail = "payloads: offsets do not match the section length";
    return false;
  }
  const unsigned char* data = offsets + offsets_size;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t begin = load_u32(offsets + 4 * std::size_t{i});
    const std::uint32_t end = load_u32(offsets + 4 * (std::size_t{i} + 1));
    // end <= size first: a later offset may be the one that decreases (found by the fuzzer).
    if (end < begin || end > size || !is_valid_utf8(data + begin, end - begin)) {
      detail = "payloads: offsets decrease or a payload is not UTF-8";
      return false;
    }
  }
  out.key = std::string_view(reinterpret_cast<const char*>(key), key_length);
  out.offsets = offsets;
  out.data = data;
  out.present = true;
  return true;
}

std::string_view payload_at(const PayloadsView& view, std::uint32_t index) noexcept {
  if (!view.present) return {};
  const std::uint32_t begin = load_u32(view.offsets + 4 * std::size_t{index});
  const std::uint32_t end = load_u32(view.offsets + 4 * (std::size_t{index} + 1));
  return {reinterpret_cast<const char*>(view.data + begin), end - begin};
}

}  // namespace urbanpvs::runtime::detail
