// SPDX-License-Identifier: MIT
// Bad input is refused with the right status, whatever the damage: wrong magic or version,
// truncation at every length, every flipped byte, trailing bytes, and counts, offsets and
// encodings that overflow or contradict each other (edited behind valid checksums).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "FileSurgery.hpp"
#include "GoldenBake.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

namespace rt = urbanpvs::runtime;
using namespace urbanpvs::test;
using rt::Status;

enum Id : std::uint32_t { kMeta = 1, kObjects = 2, kCells = 3, kGrid = 4, kPvs = 5, kPayloads = 6 };

Bytes golden() {
  return rt::encode(golden_bake(), golden_options());
}

Status load(const Bytes& b, rt::LoadError* error = nullptr, bool verify = true) {
  rt::PvsFile file;
  rt::LoadOptions options;
  options.verify_checksums = verify;
  const Status s = rt::PvsFile::open(b.data(), b.size(), file, options, error);
  EXPECT_EQ(file.is_open(), s == Status::kOk);
  return s;
}

/// The status, checked to be the same with and without checksum verification (the edit was
/// resealed, so only the structural checks can catch it), and the section it names.
void expect_malformed(const Bytes& b, Status status, std::uint32_t section) {
  rt::LoadError error;
  EXPECT_EQ(load(b, &error), status) << error.detail;
  EXPECT_EQ(error.section_id, section) << error.detail;
  EXPECT_EQ(load(b, nullptr, false), status);
}

Bytes section_bytes(const Bytes& file, std::uint32_t id) {
  const SectionEntry e = section(file, id);
  return Bytes(file.begin() + static_cast<long>(e.offset),
               file.begin() + static_cast<long>(e.offset + e.length));
}

/// `file` with section `id` edited by `edit` (the checksums resealed).
template <class Edit>
Bytes with_section_edit(const Bytes& file, std::uint32_t id, Edit edit) {
  Bytes s = section_bytes(file, id);
  edit(s);
  Bytes b = file;
  replace_section(b, id, s);
  return b;
}

/// A file from sections, written from FORMAT.md: version, features and extra header bytes free.
Bytes build(std::uint16_t minor, std::uint32_t features,
            const std::vector<std::pair<std::uint32_t, Bytes>>& sections, std::size_t extra = 0) {
  const std::size_t header = 40 + 24 * sections.size() + extra;
  Bytes out(header, std::byte{0});
  std::memcpy(out.data(), rt::format::kMagic, 8);
  put_u16(out, 8, 1);
  put_u16(out, 10, minor);
  put_u32(out, 12, static_cast<std::uint32_t>(header));
  put_u32(out, 24, static_cast<std::uint32_t>(sections.size()));
  put_u32(out, 28, features);
  for (std::size_t i = 0; i < sections.size(); ++i) {
    put_u32(out, 40 + 24 * i, sections[i].first);
    put_u64(out, 40 + 24 * i + 8, out.size());
    put_u64(out, 40 + 24 * i + 16, sections[i].second.size());
    out.insert(out.end(), sections[i].second.begin(), sections[i].second.end());
  }
  put_u64(out, 16, out.size());
  reseal(out);
  return out;
}

std::vector<std::pair<std::uint32_t, Bytes>> golden_sections() {
  const Bytes g = golden();
  std::vector<std::pair<std::uint32_t, Bytes>> s;
  for (std::uint32_t id = 1; id <= 5; ++id) s.emplace_back(id, section_bytes(g, id));
  return s;
}

TEST(Rejection, BadMagic) {
  Bytes b = golden();
  b[1] = std::byte{'X'};
  EXPECT_EQ(load(b), Status::kBadMagic);
  const char gif[] = "GIF89a-not-a-pvs-file-at-all-padding-padding-padding";
  Bytes other(sizeof gif);
  std::memcpy(other.data(), gif, sizeof gif);
  EXPECT_EQ(load(other), Status::kBadMagic);
  EXPECT_EQ(load(Bytes(3, std::byte{'G'})), Status::kBadMagic);
  EXPECT_EQ(load(Bytes{}), Status::kTruncated);
  rt::PvsFile file;
  EXPECT_EQ(rt::PvsFile::open(nullptr, 0, file), Status::kTruncated);
  EXPECT_EQ(rt::PvsFile::open(nullptr, 5, file), Status::kInvalidArgument);
}

TEST(Rejection, OtherMajorVersions) {
  for (std::uint16_t major : {0, 3, 0xFFFF}) {
    Bytes b = golden();
    put_u16(b, 8, major);
    EXPECT_EQ(load(b), Status::kUnsupportedVersion);  // refused before the checksum is read
    reseal(b);
    EXPECT_EQ(load(b), Status::kUnsupportedVersion);
    b.resize(11);  // even when nothing else of the header is there
    EXPECT_EQ(load(b), Status::kUnsupportedVersion);
  }
}

TEST(Rejection, NewerMinorLoadsUnlessItRequiresNewFeatures) {
  auto sections = golden_sections();
  sections[0].second.insert(sections[0].second.end(), 3, std::byte{0x5A});  // appended field
  sections.emplace_back(99, Bytes(10, std::byte{7}));                       // unknown section
  const Bytes newer = build(1, 0, sections, 8);
  rt::PvsFile file;
  rt::LoadError error;
  ASSERT_EQ(rt::PvsFile::open(newer.data(), newer.size(), file, {}, &error), Status::kOk)
      << error.detail;
  EXPECT_EQ(file.minor_version(), 1);
  EXPECT_EQ(file.section_count(), 6u);
  EXPECT_EQ(file.frame().crs, "EPSG:7415");
  EXPECT_TRUE(file.is_visible(2, 3));

  for (std::uint32_t feature : {1u, 0x80000000u}) {
    EXPECT_EQ(load(build(1, feature, sections, 8)), Status::kUnsupportedFeature);
    EXPECT_EQ(load(build(0, feature, golden_sections())), Status::kUnsupportedFeature);
  }
  // The current minor version may not carry extension bytes (they would be unchecked data)...
  EXPECT_EQ(load(build(0, 0, golden_sections(), 8)), Status::kMalformedHeader);
  auto extended = golden_sections();
  extended[0].second.push_back(std::byte{1});
  expect_malformed(build(0, 0, extended), Status::kMalformedSection, kMeta);
  // ... but unknown optional sections are skipped in any version.
  auto with_unknown = golden_sections();
  with_unknown.emplace_back(42, Bytes(3, std::byte{1}));
  EXPECT_EQ(load(build(0, 0, with_unknown)), Status::kOk);
  // And the rebuilt current file loads: build() follows the spec.
  EXPECT_EQ(build(0, 0, golden_sections()), golden());
}

TEST(Rejection, TruncationAtEveryLength) {
  const Bytes b = golden();
  for (std::size_t n = 0; n < b.size(); ++n) {
    const Bytes prefix(b.begin(), b.begin() + static_cast<long>(n));
    ASSERT_EQ(load(prefix), Status::kTruncated) << "prefix of " << n << " bytes";
  }
  EXPECT_EQ(load(b), Status::kOk);
}

TEST(Rejection, EverySingleFlippedByte) {
  const Bytes b = golden();
  for (std::size_t i = 0; i < b.size(); ++i) {
    for (unsigned mask : {0x01u, 0x10u, 0x80u, 0xFFu}) {
      Bytes flipped = b;
      flipped[i] ^= static_cast<std::byte>(mask);
      ASSERT_NE(load(flipped), Status::kOk) << "byte " << i << " mask " << mask;
    }
  }
}

TEST(Rejection, TrailingBytes) {
  for (std::size_t extra : {1u, 7u, 4096u}) {
    Bytes b = golden();
    b.resize(b.size() + extra, std::byte{0});
    EXPECT_EQ(load(b), Status::kTrailingBytes);
  }
}

TEST(Rejection, ChecksumsNameTheSection) {
  for (std::uint32_t id = 1; id <= 5; ++id) {
    Bytes b = golden();
    const SectionEntry e = section(b, id);
    b[e.offset + e.length / 2] ^= std::byte{0x04};
    rt::LoadError error;
    EXPECT_EQ(load(b, &error), Status::kSectionChecksumMismatch);
    EXPECT_EQ(error.section_id, id);
    static const char* const kNames[] = {"", "metadata", "objects", "cells", "grid", "pvs"};
    EXPECT_STREQ(rt::format::section_name(error.section_id), kNames[id]);
  }
  Bytes b = golden();
  b[40 + 4] ^= std::byte{1};  // a section CRC inside the table
  EXPECT_EQ(load(b), Status::kHeaderChecksumMismatch);
}

TEST(Rejection, SectionTableOverflowsAndInconsistencies) {
  const Bytes g = golden();
  const SectionEntry pvs = section(g, kPvs);
  auto edited = [&](auto edit) {
    Bytes b = g;
    edit(b);
    reseal(b);
    return b;
  };
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u64(b, pvs.table_at + 8, UINT64_MAX - 3); })),
            Status::kMalformedHeader);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u64(b, pvs.table_at + 16, UINT64_MAX); })),
            Status::kMalformedHeader);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u64(b, pvs.table_at + 16, pvs.length - 1); })),
            Status::kMalformedHeader);  // the last byte belongs to no section
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, 24, 0xFFFFFFFFu); })), Status::kMalformedHeader);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, 24, 0x0AAAAAABu); })), Status::kMalformedHeader);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, 12, 0xFFFFFFFFu); })), Status::kTruncated);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, 12, 16); })), Status::kMalformedHeader);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u64(b, 16, UINT64_MAX); })), Status::kTruncated);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, 36, 1); })), Status::kMalformedHeader);
  // Two entries swapped: ids no longer increasing, sections no longer in file order.
  EXPECT_EQ(load(edited([&](Bytes& b) {
              put_u32(b, 40, kObjects);
              put_u32(b, 64, kMeta);
            })),
            Status::kMalformedHeader);
  // A duplicate id.
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, 64, kMeta); })), Status::kMalformedHeader);
  // An unknown id in the grid's place breaks the id order...
  const SectionEntry grid = section(g, kGrid);
  EXPECT_EQ(load(edited([&](Bytes& b) { put_u32(b, grid.table_at, 77); })),
            Status::kMalformedHeader);
  // ... and a file without a grid is missing a required section.
  auto sections = golden_sections();
  sections.erase(sections.begin() + 3);
  rt::LoadError error;
  EXPECT_EQ(load(build(0, 0, sections), &error), Status::kMissingSection);
  EXPECT_EQ(error.section_id, kGrid);
}

TEST(Rejection, ObjectCountsOffsetsAndStrings) {
  const Bytes g = golden();
  auto with = [&](auto edit) { return with_section_edit(g, kObjects, edit); };
  expect_malformed(with([](Bytes& s) { put_u32(s, 0, 0xFFFFFFFFu); }), Status::kMalformedSection,
                   kObjects);
  expect_malformed(with([](Bytes& s) { put_u32(s, 0, 121); }), Status::kMalformedSection, kObjects);
  expect_malformed(with([](Bytes& s) { put_u64(s, 8, UINT64_MAX); }), Status::kMalformedSection,
                   kObjects);
  expect_malformed(with([](Bytes& s) { s[4] = std::byte{5}; }), Status::kMalformedSection,
                   kObjects);
  expect_malformed(with([](Bytes& s) { s[5] = std::byte{1}; }), Status::kMalformedSection,
                   kObjects);
  // First record: id offset past the strings, id length overflowing, min > max, NaN.
  expect_malformed(with([](Bytes& s) { put_u32(s, 16, 0xFFFFFFF0u); }), Status::kMalformedSection,
                   kObjects);
  expect_malformed(with([](Bytes& s) { put_u32(s, 20, 0xFFFFFFFFu); }), Status::kMalformedSection,
                   kObjects);
  expect_malformed(with([](Bytes& s) { put_u32(s, 24, 0x7F800000u); }), Status::kMalformedSection,
                   kObjects);
  expect_malformed(with([](Bytes& s) { put_u32(s, 24, 0x7FC00000u); }), Status::kMalformedSection,
                   kObjects);
  // Invalid UTF-8 in the first source id (strings follow 120 records of 32 bytes).
  expect_malformed(with([](Bytes& s) { s[16 + 120 * 32] = std::byte{0xC0}; }),
                   Status::kMalformedSection, kObjects);
}

TEST(Rejection, PayloadCountsOffsetsAndText) {
  // FORMAT.md "6 — payloads": u32 objects, u32 flags, string key ("tile": 4 + 4 bytes), then
  // 121 u32 offsets from byte 16, then the payload text from byte 16 + 484.
  const Bytes g = rt::encode(golden_bake_with_payloads(), golden_options(2));
  ASSERT_EQ(load(g), Status::kOk);
  auto with = [&](auto edit) { return with_section_edit(g, kPayloads, edit); };
  expect_malformed(with([](Bytes& s) { put_u32(s, 0, 119); }), Status::kMalformedSection,
                   kPayloads);
  expect_malformed(with([](Bytes& s) { put_u32(s, 4, 1); }), Status::kMalformedSection, kPayloads);
  expect_malformed(with([](Bytes& s) { put_u32(s, 8, 0xFFFFFFF0u); }), Status::kMalformedSection,
                   kPayloads);
  expect_malformed(with([](Bytes& s) { s[12] = std::byte{0xFF}; }), Status::kMalformedSection,
                   kPayloads);  // the key is not UTF-8
  expect_malformed(with([](Bytes& s) { put_u32(s, 16, 1); }), Status::kMalformedSection,
                   kPayloads);  // the first offset is not 0
  expect_malformed(with([](Bytes& s) { put_u32(s, 20, 0xFFFFFFF0u); }), Status::kMalformedSection,
                   kPayloads);  // an offset past the text
  expect_malformed(with([](Bytes& s) { put_u32(s, 16 + 4 * 120, 3); }), Status::kMalformedSection,
                   kPayloads);  // the last offset does not end the section
  expect_malformed(with([](Bytes& s) { put_u32(s, 24, 2); }), Status::kMalformedSection,
                   kPayloads);  // offsets decrease (object 1 ends before it starts)
  expect_malformed(with([](Bytes& s) { s[16 + 484] = std::byte{0xC0}; }), Status::kMalformedSection,
                   kPayloads);  // the first payload is not UTF-8
  expect_malformed(with([](Bytes& s) { s.push_back(std::byte{0}); }), Status::kMalformedSection,
                   kPayloads);  // trailing bytes in a file of this reader's version
}

TEST(Rejection, MetadataCellsAndGrid) {
  const Bytes g = golden();
  auto with = [&](std::uint32_t id, auto edit) { return with_section_edit(g, id, edit); };
  expect_malformed(with(kMeta, [](Bytes& s) { put_u32(s, 4, 0xFFFFFFFFu); }),
                   Status::kMalformedSection, kMeta);
  expect_malformed(with(kMeta, [](Bytes& s) { s[8] = std::byte{0xFF}; }), Status::kMalformedSection,
                   kMeta);
  expect_malformed(with(kMeta, [](Bytes& s) { put_u64(s, 17, 0x7FF8000000000000ULL); }),
                   Status::kMalformedSection, kMeta);
  // Property count (at 4 + 4 + 9 + 3*8 + 3*8 + 5*8 + 8 = 113) larger than the section can hold.
  expect_malformed(with(kMeta, [](Bytes& s) { put_u32(s, 113, 0x7FFFFFFFu); }),
                   Status::kMalformedSection, kMeta);
  expect_malformed(with(kMeta, [](Bytes& s) { put_u32(s, 113, 3); }), Status::kMalformedSection,
                   kMeta);
  expect_malformed(with(kMeta, [](Bytes& s) { s.pop_back(); }), Status::kMalformedSection, kMeta);

  expect_malformed(with(kCells, [](Bytes& s) { put_u32(s, 0, 0x0FFFFFFFu); }),
                   Status::kMalformedSection, kCells);
  expect_malformed(with(kCells, [](Bytes& s) { put_u32(s, 0, 0xFFFFFFFFu); }),
                   Status::kMalformedSection, kCells);
  expect_malformed(with(kCells, [](Bytes& s) { put_u32(s, 8 + 64, 6); }), Status::kMalformedSection,
                   kCells);
  expect_malformed(with(kCells, [](Bytes& s) { put_u64(s, 8 + 48, 0x7FF0000000000000ULL); }),
                   Status::kMalformedSection, kCells);  // z_min = inf
  expect_malformed(with(kCells, [](Bytes& s) { put_u64(s, 8, 0xFFF8000000000000ULL); }),
                   Status::kMalformedSection, kCells);  // NaN vertex

  expect_malformed(with(kGrid,
                        [](Bytes& s) {
                          put_u32(s, 32, 0xFFFFFFFFu);
                          put_u32(s, 36, 0xFFFFFFFFu);
                        }),
                   Status::kMalformedSection, kGrid);
  expect_malformed(with(kGrid, [](Bytes& s) { put_u32(s, 40, 0xFFFFFFFFu); }),
                   Status::kMalformedSection, kGrid);
  expect_malformed(with(kGrid, [](Bytes& s) { put_u64(s, 16, 0); }), Status::kMalformedSection,
                   kGrid);
  expect_malformed(with(kGrid, [](Bytes& s) { put_u64(s, 16, 0xBFF0000000000000ULL); }),
                   Status::kMalformedSection, kGrid);  // negative cell size
  // Moving the grid makes it disagree with the cells it indexes.
  expect_malformed(with(kGrid, [](Bytes& s) { put_u64(s, 0, 0x4059000000000000ULL); }),
                   Status::kMalformedSection, kGrid);
  // The last entry of the index (a cell index) out of range.
  expect_malformed(with(kGrid, [](Bytes& s) { put_u32(s, s.size() - 4, 6); }),
                   Status::kMalformedSection, kGrid);
}

// --- hand-made pvs sections -------------------------------------------------------------------

Bytes varints(std::initializer_list<std::uint32_t> values) {
  Bytes out;
  for (std::uint32_t v : values) {
    do {
      out.push_back(static_cast<std::byte>((v & 0x7F) | (v >= 0x80 ? 0x80 : 0)));
      v >>= 7;
    } while (v != 0);
  }
  return out;
}

/// delta list payload of sorted ids.
Bytes delta(std::initializer_list<std::uint32_t> ids) {
  Bytes out = varints({0, static_cast<std::uint32_t>(ids.size())});
  std::uint64_t next = 0;
  for (std::uint32_t id : ids) {
    const Bytes g = varints({static_cast<std::uint32_t>(id - next)});
    out.insert(out.end(), g.begin(), g.end());
    next = std::uint64_t{id} + 1;
  }
  return out;
}

/// diff payload; removed and added are already gap-coded.
Bytes diff(std::uint32_t cell, std::uint32_t ref, std::uint32_t count, Bytes removed_gaps,
           std::uint32_t removed, Bytes added_gaps, std::uint32_t added) {
  const std::uint32_t d = ref - cell;
  Bytes out = varints({2, count, (d << 1) ^ (0u - (d >> 31)), removed, added});
  out.insert(out.end(), removed_gaps.begin(), removed_gaps.end());
  out.insert(out.end(), added_gaps.begin(), added_gaps.end());
  return out;
}

Bytes pvs_section(const std::vector<Bytes>& payloads, std::uint32_t max_chain) {
  Bytes out(8 + 4 * (payloads.size() + 1), std::byte{0});
  put_u32(out, 0, static_cast<std::uint32_t>(payloads.size()));
  put_u32(out, 4, max_chain);
  std::uint32_t offset = 0;
  for (std::size_t i = 0; i < payloads.size(); ++i) {
    out.insert(out.end(), payloads[i].begin(), payloads[i].end());
    offset += static_cast<std::uint32_t>(payloads[i].size());
    put_u32(out, 8 + 4 * (i + 1), offset);
  }
  return out;
}

Bytes with_pvs(const std::vector<Bytes>& payloads, std::uint32_t max_chain = 4) {
  Bytes b = golden();
  replace_section(b, kPvs, pvs_section(payloads, max_chain));
  return b;
}

TEST(Rejection, HandMadeChainDecodesAsSpecified) {
  // Cell 0 full; 1..4 a chain of four diffs; 5 a diff against 0.
  const Bytes b =
      with_pvs({delta({1, 5, 9}), diff(1, 0, 3, varints({0}), 1, varints({10}), 1),  // 5 9 10
                diff(2, 1, 5, {}, 0, varints({0, 1}), 2),                            // 0 2 5 9 10
                diff(3, 2, 3, varints({0, 1}), 2, {}, 0),          // 2 9 10 (-0 -5)
                diff(4, 3, 3, varints({2}), 1, varints({39}), 1),  // 2 9 39
                diff(5, 0, 0, varints({0, 0, 0}), 3, {}, 0)});     // empty
  rt::PvsFile file;
  rt::LoadError error;
  ASSERT_EQ(rt::PvsFile::open(b.data(), b.size(), file, {}, &error), Status::kOk) << error.detail;
  rt::PvsDecoder decoder(file);
  const std::vector<std::vector<std::uint32_t>> want = {{1, 5, 9},  {5, 9, 10}, {0, 2, 5, 9, 10},
                                                        {2, 9, 10}, {2, 9, 39}, {}};
  for (std::uint32_t c = 0; c < 6; ++c) {
    ASSERT_EQ(decoder.decode(c), Status::kOk);
    EXPECT_EQ(std::vector<std::uint32_t>(decoder.begin(), decoder.end()), want[c]) << c;
    for (std::uint32_t o = 0; o < 40; ++o) {
      EXPECT_EQ(file.is_visible(c, o),
                std::find(want[c].begin(), want[c].end(), o) != want[c].end());
    }
  }
  EXPECT_EQ(file.decode_buffer_size(), 2u * 5u);
}

TEST(Rejection, BadPvsEncodings) {
  const Bytes ok = delta({1});
  auto expect_bad = [](const Bytes& b) { expect_malformed(b, Status::kMalformedSection, kPvs); };
  // A cycle, a chain longer than the format allows, a chain longer than declared.
  expect_bad(with_pvs({diff(0, 1, 0, {}, 0, {}, 0), diff(1, 0, 0, {}, 0, {}, 0), ok, ok, ok, ok}));
  expect_bad(with_pvs({ok, diff(1, 0, 1, {}, 0, {}, 0), diff(2, 1, 1, {}, 0, {}, 0),
                       diff(3, 2, 1, {}, 0, {}, 0), diff(4, 3, 1, {}, 0, {}, 0),
                       diff(5, 4, 1, {}, 0, {}, 0)}));
  expect_bad(
      with_pvs({ok, diff(1, 0, 1, {}, 0, {}, 0), diff(2, 1, 1, {}, 0, {}, 0), ok, ok, ok}, 1));
  // Self reference, reference out of range.
  expect_bad(with_pvs({ok, diff(1, 1, 1, {}, 0, {}, 0), ok, ok, ok, ok}));
  expect_bad(with_pvs({ok, diff(1, 6, 1, {}, 0, {}, 0), ok, ok, ok, ok}));
  // Removal past the reference list; addition duplicating a kept id; wrong count.
  expect_bad(with_pvs({ok, diff(1, 0, 0, varints({1}), 1, {}, 0), ok, ok, ok, ok}));
  expect_bad(with_pvs({ok, diff(1, 0, 2, {}, 0, varints({1}), 1), ok, ok, ok, ok}));
  expect_bad(with_pvs({ok, diff(1, 0, 3, {}, 0, varints({2}), 1), ok, ok, ok, ok}));
  // Object index out of range, unsorted (gap wraps), count larger than the object count.
  expect_bad(with_pvs({delta({120}), ok, ok, ok, ok, ok}));
  expect_bad(with_pvs({varints({0, 2, 0xFFFFFFFFu, 3}), ok, ok, ok, ok, ok}));
  expect_bad(with_pvs({varints({0, 121}), ok, ok, ok, ok, ok}));
  // Unknown kind, non-minimal varint, trailing payload bytes, payload cut short.
  expect_bad(with_pvs({varints({3, 0}), ok, ok, ok, ok, ok}));
  Bytes overlong = varints({0, 1});
  overlong.push_back(std::byte{0x81});
  overlong.push_back(std::byte{0x00});
  expect_bad(with_pvs({overlong, ok, ok, ok, ok, ok}));
  Bytes trailing = delta({1});
  trailing.push_back(std::byte{0});
  expect_bad(with_pvs({trailing, ok, ok, ok, ok, ok}));
  expect_bad(with_pvs({varints({0, 2, 1}), ok, ok, ok, ok, ok}));
  // Bitsets: zero first byte (non-canonical), popcount different from the count, bits past
  // the last object.
  expect_bad(with_pvs({varints({1, 1, 0, 2, 0, 1}), ok, ok, ok, ok, ok}));
  expect_bad(with_pvs({varints({1, 2, 0, 1, 1}), ok, ok, ok, ok, ok}));
  Bytes past_end = varints({1, 1, 15, 1});  // byte 15: ids 120..127, above the 120 objects
  past_end.push_back(std::byte{0x80});
  expect_bad(with_pvs({past_end, ok, ok, ok, ok, ok}));
  // Section-level: wrong cell count, chain bound above the format's, offsets not increasing,
  // offsets past the payload, overflowing cell count.
  Bytes b = with_pvs({ok, ok, ok, ok, ok, ok});
  auto edit_pvs = [&](auto edit) {
    Bytes s = section_bytes(b, kPvs);
    edit(s);
    Bytes out = b;
    replace_section(out, kPvs, s);
    return out;
  };
  expect_bad(edit_pvs([](Bytes& s) { put_u32(s, 0, 5); }));
  expect_bad(edit_pvs([](Bytes& s) { put_u32(s, 0, 0xFFFFFFFFu); }));
  expect_bad(edit_pvs([](Bytes& s) { put_u32(s, 4, 5); }));
  expect_bad(edit_pvs([](Bytes& s) { put_u32(s, 8 + 4 * 2, 1); }));
  expect_bad(edit_pvs([](Bytes& s) { put_u32(s, 8 + 4 * 6, 1000); }));
  expect_bad(edit_pvs([](Bytes& s) { put_u32(s, 8, 1); }));
}

// --- hand-made coded pvs sections (format 2.2), written from FORMAT.md ---------------------

/// An LSB-first bit stream of exp-Golomb codes: g with order k is n - k - 1 zeros, a one, then
/// the n - 1 low bits of v = g + 2^k (n = bit width of v), least significant first.
class Codes {
 public:
  Codes& code(std::uint64_t g, unsigned k) {
    const std::uint64_t v = g + (std::uint64_t{1} << k);
    unsigned n = 0;
    while ((v >> n) != 0) ++n;
    for (unsigned i = 0; i + k + 1 < n; ++i) bit(0);
    bit(1);
    for (unsigned i = 0; i + 1 < n; ++i) bit((v >> i) & 1);
    return *this;
  }
  /// Codes of the gaps of the increasing `values`.
  Codes& gaps(std::initializer_list<std::uint32_t> values, unsigned k) {
    std::uint64_t next = 0;
    for (std::uint32_t v : values) {
      code(v - next, k);
      next = std::uint64_t{v} + 1;
    }
    return *this;
  }
  Codes& bit(std::uint64_t b) {
    if (used_ % 8 == 0) bytes_.push_back(std::byte{0});
    bytes_.back() |= static_cast<std::byte>(b << (used_ % 8));
    ++used_;
    return *this;
  }
  Bytes bytes() const { return bytes_; }

 private:
  Bytes bytes_;
  unsigned used_ = 0;
};

Bytes cat(Bytes a, const Bytes& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

/// A coded delta list: kind byte k << 2, varint count, codes.
Bytes coded_delta(unsigned k, std::initializer_list<std::uint32_t> ids) {
  Bytes out{static_cast<std::byte>(k << 2)};
  return cat(cat(out, varints({static_cast<std::uint32_t>(ids.size())})),
             Codes().gaps(ids, k).bytes());
}

/// The reference code of a coded diff naming `ref` by its distance: zigzag(ref - cell) + 3
/// (codes 0..2 are neighbour slots).
std::uint32_t distance_code(std::uint32_t cell, std::uint32_t ref) {
  const std::uint32_t d = ref - cell;
  return ((d << 1) ^ (0u - (d >> 31))) + 3;
}

/// A coded diff: kind byte 2 | kr << 2 | ka << 5, varint reference code, varint r, varint a
/// (no count: it is derived), then one bit stream.
Bytes coded_diff(std::uint32_t reference_code, unsigned kr,
                 std::initializer_list<std::uint32_t> removed, unsigned ka,
                 std::initializer_list<std::uint32_t> added) {
  Bytes out{static_cast<std::byte>(2 | kr << 2 | ka << 5)};
  out = cat(out, varints({reference_code, static_cast<std::uint32_t>(removed.size()),
                          static_cast<std::uint32_t>(added.size())}));
  return cat(out, Codes().gaps(removed, kr).gaps(added, ka).bytes());
}

/// Header (cells, chain, block shift, payload size), then per block a u32 start and u16
/// offsets from it, then the payloads.
Bytes coded_section(const std::vector<Bytes>& payloads, std::uint32_t max_chain,
                    std::uint32_t shift) {
  Bytes out(16, std::byte{0}), index, blob;
  put_u32(out, 0, static_cast<std::uint32_t>(payloads.size()));
  put_u32(out, 4, max_chain);
  put_u32(out, 8, shift);
  std::uint32_t block_start = 0;
  for (std::size_t c = 0; c < payloads.size(); ++c) {
    const auto start = static_cast<std::uint32_t>(blob.size());
    if (c % (std::size_t{1} << shift) == 0) {
      block_start = start;
      index.resize(index.size() + 4);
      put_u32(index, index.size() - 4, start);
    } else {
      index.resize(index.size() + 2);
      put_u16(index, index.size() - 2, static_cast<std::uint16_t>(start - block_start));
    }
    blob = cat(blob, payloads[c]);
  }
  put_u32(out, 12, static_cast<std::uint32_t>(blob.size()));
  return cat(cat(out, index), blob);
}

/// The 2.2 golden file with this pvs section.
Bytes with_coded(const Bytes& section) {
  Bytes b = rt::encode(golden_bake(), golden_options(2, 2));
  replace_section(b, kPvs, section);
  return b;
}

/// The same content as HandMadeChainDecodesAsSpecified, coded. The golden cells are a strip of
/// triangles: cell c's neighbours (GoldenTest) are 0: {-, 1, -}, 1: {2, -, 0}, 2: {-, 3, 1},
/// 3: {4, -, 2}, 4: {-, 5, 3}, 5: {-, -, 4}; references name them by slot where they can.
std::vector<Bytes> coded_chain() {
  return {coded_delta(2, {1, 5, 9}),
          coded_diff(2, 0, {0}, 3, {10}),                         // 1 -> 0, slot 2
          coded_diff(2, 0, {}, 0, {0, 2}),                        // 2 -> 1, slot 2
          coded_diff(distance_code(3, 2), 1, {0, 2}, 0, {}),      // 3 -> 2 by distance
          coded_diff(2, 7, {2}, 5, {39}),                         // 4 -> 3, slot 2
          coded_diff(distance_code(5, 0), 0, {0, 1, 2}, 0, {})};  // 5 -> 0 by distance
}

TEST(Rejection, HandMadeCodedChainDecodesAsSpecified) {
  const std::vector<std::vector<std::uint32_t>> want = {{1, 5, 9},  {5, 9, 10}, {0, 2, 5, 9, 10},
                                                        {2, 9, 10}, {2, 9, 39}, {}};
  for (std::uint32_t shift : {0u, 1u, 2u, 4u}) {
    SCOPED_TRACE("block shift " + std::to_string(shift));
    const Bytes b = with_coded(coded_section(coded_chain(), 4, shift));
    rt::PvsFile file;
    rt::LoadError error;
    ASSERT_EQ(rt::PvsFile::open(b.data(), b.size(), file, {}, &error), Status::kOk) << error.detail;
    EXPECT_EQ(file.minor_version(), 2);
    rt::PvsDecoder decoder(file);
    for (std::uint32_t c = 0; c < 6; ++c) {
      ASSERT_EQ(decoder.decode(c), Status::kOk);
      EXPECT_EQ(std::vector<std::uint32_t>(decoder.begin(), decoder.end()), want[c]) << c;
      EXPECT_EQ(file.pvs_size(c), want[c].size());
      for (std::uint32_t o = 0; o < 40; ++o) {
        EXPECT_EQ(file.is_visible(c, o),
                  std::find(want[c].begin(), want[c].end(), o) != want[c].end());
      }
    }
    rt::PvsEncodingInfo info;
    ASSERT_EQ(file.pvs_encoding(4, info), Status::kOk);
    EXPECT_EQ(info.payload_bytes, coded_chain()[4].size());
  }
  // The encoder's own 2.2 file decodes to the content of the plain one (GoldenTest checks both).
  const Bytes ours = rt::encode(golden_bake(), golden_options(2, 2));
  EXPECT_EQ(load(ours), Status::kOk);
}

TEST(Rejection, BadCodedPvsEncodings) {
  auto expect_bad = [](const std::vector<Bytes>& payloads, std::uint32_t shift = 2) {
    expect_malformed(with_coded(coded_section(payloads, 4, shift)), Status::kMalformedSection,
                     kPvs);
  };
  const Bytes ok = coded_delta(0, {1});
  auto cells = [&](const Bytes& first) { return std::vector<Bytes>{first, ok, ok, ok, ok, ok}; };
  // A list's order of 32 (bit 7 set), order bits on a bitset, kind 3.
  expect_bad(cells(cat(Bytes{std::byte{0x80}}, varints({0}))));
  Bytes bitset = cat(Bytes{std::byte{1 | 4}}, varints({1, 0, 1}));
  bitset.push_back(std::byte{2});
  expect_bad(cells(bitset));
  expect_bad(cells(cat(Bytes{std::byte{3}}, varints({0}))));
  // Padding bits not zero, a trailing byte, a code that runs past the payload, ids out of range
  // or wrapping past 2^32.
  Bytes padded = coded_delta(0, {1});  // "01" then padding
  padded.back() |= std::byte{0x80};
  expect_bad(cells(padded));
  expect_bad(cells(cat(coded_delta(0, {1}), Bytes{std::byte{0}})));
  expect_bad(cells(cat(cat(Bytes{std::byte{0}}, varints({2})), Codes().gaps({3}, 0).bytes())));
  expect_bad(cells(coded_delta(3, {120})));
  expect_bad(cells(cat(cat(Bytes{std::byte{31 << 2}}, varints({2})),
                       Codes().code(0xFFFFFFFFu, 31).code(1, 31).bytes())));
  // A diff: removal past its reference, an addition equal to a kept id, a removal code cut
  // short (the additions would begin inside it).
  auto diffs = [&](const Bytes& d) { return std::vector<Bytes>{ok, d, ok, ok, ok, ok}; };
  expect_bad(diffs(coded_diff(2, 0, {1}, 0, {})));
  expect_bad(diffs(coded_diff(2, 1, {}, 1, {1})));
  Bytes cut = coded_diff(2, 7, {0}, 0, {});
  cut.pop_back();
  expect_bad(diffs(cut));
  // The derived count: more removals than the reference holds; a chain adding past the object
  // count is caught as an index out of range.
  expect_bad(diffs(coded_diff(2, 0, {0, 1}, 0, {})));
  // References: an empty neighbour slot (cell 1's slot 1), slot 3 and up are distances (3:
  // the cell itself), a distance out of range, a cycle through slots (0 <-> 1).
  expect_bad(diffs(coded_diff(1, 0, {}, 0, {})));
  expect_bad(diffs(coded_diff(3, 0, {}, 0, {})));
  expect_bad(diffs(coded_diff(distance_code(1, 6), 0, {}, 0, {})));
  expect_bad({coded_diff(1, 0, {}, 0, {}), coded_diff(2, 0, {}, 0, {}), ok, ok, ok, ok});
  // Section level: block shift above 4, payload size not the section's, first start not 0,
  // an index that goes back.
  expect_bad(coded_chain(), 5);
  Bytes base = coded_section(coded_chain(), 4, 2);
  auto edited_section = [&](auto edit) {
    Bytes s = base;
    edit(s);
    expect_malformed(with_coded(s), Status::kMalformedSection, kPvs);
  };
  edited_section([](Bytes& s) { put_u32(s, 12, 1000); });
  edited_section([](Bytes& s) { put_u32(s, 16, 1); });
  edited_section([](Bytes& s) { put_u16(s, 16 + 4 + 2, 1); });  // cell 2 starts before cell 1
  // The feature bit decides the layout: a coded section without it, a plain one with it.
  Bytes unmarked = rt::encode(golden_bake(), golden_options(2, 0));
  replace_section(unmarked, kPvs, base);
  expect_malformed(unmarked, Status::kMalformedSection, kPvs);
  expect_malformed(with_coded(section_bytes(rt::encode(golden_bake(), golden_options(2, 0)), kPvs)),
                   Status::kMalformedSection, kPvs);
  // And a 1.x file may not ask for the coded PVS at all.
  EXPECT_EQ(load(build(0, rt::format::kFeatureCodedPvs, golden_sections())),
            Status::kUnsupportedFeature);
}

}  // namespace
