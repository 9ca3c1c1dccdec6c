// SPDX-License-Identifier: MIT
// The committed files of every format version (v1_0.pvs, v2_0.pvs: the same bake; v2_1.pvs adds
// payloads; v2_2.pvs is v2_1's bake with the coded PVS) must decode forever to the values
// written below (not regenerated from the decoder), and the encoder must still produce exactly
// their bytes when asked for that version.
#include <gtest/gtest.h>

#include "FileSurgery.hpp"
#include "GoldenBake.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

namespace rt = urbanpvs::runtime;

/// A committed golden file: its version, and the bake behind it.
struct Version {
  std::uint16_t major;
  std::uint16_t minor;
  std::string name() const { return "v" + std::to_string(major) + "_" + std::to_string(minor); }
  bool payloads() const { return major == 2 && minor >= 1; }
};

std::string golden_path(const Version& v) {
  return std::string(URBANPVS_RUNTIME_GOLDEN_DIR) + "/" + v.name() + ".pvs";
}

std::vector<std::uint32_t> pvs(const rt::PvsFile& file, std::uint32_t cell) {
  rt::PvsDecoder decoder(file);
  EXPECT_EQ(decoder.decode(cell), rt::Status::kOk);
  return {decoder.begin(), decoder.end()};
}

class Golden : public ::testing::TestWithParam<Version> {};

TEST_P(Golden, DecodesToTheRecordedContent) {
  const Version version = GetParam();
  const std::uint16_t major = version.major;
  rt::PvsFile file;
  rt::LoadError error;
  rt::LoadOptions options;
  options.expand_pvs = major == 2 && version.minor == 0;  // both query paths
  ASSERT_EQ(rt::PvsFile::open_file(golden_path(version).c_str(), file, options, &error),
            rt::Status::kOk)
      << error.detail;
  EXPECT_EQ(file.major_version(), major);
  EXPECT_EQ(file.minor_version(), version.minor);
  // 1.x: metadata, objects, cells, grid, pvs. 2.x: the grid is built at load. 2.1: payloads.
  const std::vector<std::uint32_t> ids =
      major == 1 ? std::vector<std::uint32_t>{1, 2, 3, 4, 5}
                 : (version.payloads() ? std::vector<std::uint32_t>{1, 2, 3, 5, 6}
                                       : std::vector<std::uint32_t>{1, 2, 3, 5});
  ASSERT_EQ(file.section_count(), ids.size());
  for (std::uint32_t i = 0; i < ids.size(); ++i) EXPECT_EQ(file.section(i).id, ids[i]);

  const rt::FrameInfo frame = file.frame();
  EXPECT_EQ(frame.crs, "EPSG:7415");
  EXPECT_FALSE(frame.geographic);
  EXPECT_EQ(frame.origin, (std::array<double, 3>{85000.0, 446000.0, -1.5}));
  const rt::BakeSettings s = file.settings();
  EXPECT_EQ(s.epsilon_m, 0.25);
  EXPECT_EQ(s.pixel_size_m, 0.5);
  EXPECT_EQ(s.max_cell_edge_m, 10.0);
  EXPECT_EQ(s.eye_min_m, 1.5);
  EXPECT_EQ(s.eye_max_m, 2.0);
  EXPECT_EQ(s.input_hash, 0x0123456789ABCDEFULL);
  ASSERT_EQ(file.property_count(), 2u);
  std::string_view key, value;
  ASSERT_EQ(file.property(0, key, value), rt::Status::kOk);
  EXPECT_EQ(key, "city");
  EXPECT_EQ(value, "Delft \"centrum\"");
  ASSERT_EQ(file.property(1, key, value), rt::Status::kOk);
  EXPECT_EQ(key, "note");
  EXPECT_EQ(value, "caf\xC3\xA9\n\ttab");

  ASSERT_EQ(file.object_count(), 120u);
  rt::ObjectInfo o;
  ASSERT_EQ(file.object(0, o), rt::Status::kOk);
  EXPECT_EQ(o.source_id, "NL.IMBAG.Pand.1000");
  EXPECT_EQ(o.bbox, (rt::Bbox{-4.0, 12.0, 0.0, 1.5, 16.25, 6.0}));
  ASSERT_EQ(file.object(23, o), rt::Status::kOk);
  EXPECT_EQ(o.source_id, "NL.IMBAG.Pand.1023");
  EXPECT_EQ(o.bbox, (rt::Bbox{84.0, 20.0, 0.0, 89.5, 24.25, 8.0}));
  ASSERT_EQ(file.object(39, o), rt::Status::kOk);
  EXPECT_EQ(o.source_id, "NL.IMBAG.Pand.1039");
  EXPECT_EQ(o.bbox, (rt::Bbox{20.0, 36.0, 0.0, 25.5, 40.25, 10.0}));
  ASSERT_EQ(file.object(119, o), rt::Status::kOk);
  EXPECT_EQ(o.source_id, "NL.IMBAG.Pand.1119");
  EXPECT_EQ(o.bbox, (rt::Bbox{84.0, 84.0, 0.0, 89.5, 88.25, 6.0}));
  EXPECT_EQ(file.object(120, o), rt::Status::kOutOfRange);
  EXPECT_EQ(file.has_payloads(), version.payloads());
  EXPECT_EQ(file.payload_key(), version.payloads() ? "tile" : "");
  const std::pair<std::uint32_t, std::string_view> payloads[] = {
      {0, "tiles/0/0.glb"}, {2, ""}, {23, "caf\xC3\xA9/23"}, {118, "tiles/9/10.glb"}, {119, ""}};
  for (const auto& [index, payload] : payloads) {
    ASSERT_EQ(file.object(index, o), rt::Status::kOk);
    EXPECT_EQ(o.payload, version.payloads() ? payload : "") << index;
  }

  ASSERT_EQ(file.cell_count(), 6u);
  struct Expected {
    double x[3], y[3], z_min, z_max;
    std::uint32_t n[3];
  };
  const std::uint32_t none = rt::kNoCell;
  const Expected cells[6] = {
      {{0, 10, 0}, {0, 0, 10}, 1.5, 2.0, {none, 1, none}},
      {{10, 10, 0}, {0, 10, 10}, 1.5, 2.0, {2, none, 0}},
      {{10, 20, 10}, {0, 0, 10}, 1.5, 3.0, {none, 3, 1}},
      {{20, 20, 10}, {0, 10, 10}, 1.5, 2.0, {4, none, 2}},
      {{20, 30, 20}, {0, 0, 10}, 1.5, 2.0, {none, 5, 3}},
      {{30, 30, 20}, {0, 10, 10}, 0.5, 2.0, {none, none, 4}},
  };
  for (std::uint32_t c = 0; c < 6; ++c) {
    rt::CellGeometry g;
    ASSERT_EQ(file.cell(c, g), rt::Status::kOk);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(g.triangle[k].x, cells[c].x[k]) << c;
      EXPECT_EQ(g.triangle[k].y, cells[c].y[k]) << c;
      EXPECT_EQ(g.neighbours[k], cells[c].n[k]) << c;
    }
    EXPECT_EQ(g.z_min, cells[c].z_min);
    EXPECT_EQ(g.z_max, cells[c].z_max);
  }

  EXPECT_EQ(pvs(file, 0), (std::vector<std::uint32_t>{}));
  EXPECT_EQ(pvs(file, 1), (std::vector<std::uint32_t>{0, 13, 27, 41, 55, 69, 83, 97, 111, 119}));
  EXPECT_EQ(pvs(file, 2), (std::vector<std::uint32_t>{0, 3, 13, 27, 41, 55, 69, 83, 97, 111}));
  std::vector<std::uint32_t> dense;  // every index but 4, 9, 14, ...
  for (std::uint32_t i = 0; i < 120; ++i) {
    if (i % 5 != 4) dense.push_back(i);
  }
  ASSERT_EQ(dense.size(), 96u);
  EXPECT_EQ(pvs(file, 3), dense);
  EXPECT_EQ(pvs(file, 4), std::vector<std::uint32_t>(dense.begin() + 1, dense.end()));
  EXPECT_EQ(pvs(file, 5), (std::vector<std::uint32_t>{7, 38}));

  // Every encoding appears: empty/delta, diff, bitset.
  using Kind = rt::format::PvsKind;
  const Kind kinds[6] = {Kind::kDeltaList, Kind::kDeltaList, Kind::kDiff,
                         Kind::kBitset,    Kind::kDiff,      Kind::kDeltaList};
  const std::uint32_t refs[6] = {none, none, 1, none, 3, none};
  for (std::uint32_t c = 0; c < 6; ++c) {
    rt::PvsEncodingInfo info;
    ASSERT_EQ(file.pvs_encoding(c, info), rt::Status::kOk);
    EXPECT_EQ(info.kind, static_cast<std::uint8_t>(kinds[c])) << c;
    EXPECT_EQ(info.reference, refs[c]) << c;
  }

  // Point location, in local coordinates: interiors, a shared edge (lowest index wins), z.
  EXPECT_EQ(file.locate(2, 2, 1.75), 0u);
  EXPECT_EQ(file.locate(8, 8, 1.75), 1u);
  EXPECT_EQ(file.locate(5, 5, 1.75), 0u);   // on the shared diagonal of cells 0 and 1
  EXPECT_EQ(file.locate(10, 5, 1.75), 1u);  // on the edge between 1 and 2
  EXPECT_EQ(file.locate(12, 2, 2.5), 2u);   // only cell 2 reaches 2.5 m
  EXPECT_EQ(file.locate(12, 2, 3.5), none);
  EXPECT_EQ(file.locate(29, 9, 1.0), 5u);
  EXPECT_EQ(file.locate(31, 5, 1.75), none);
  EXPECT_TRUE(file.is_visible(4, 1));
  EXPECT_FALSE(file.is_visible(4, 0));
  EXPECT_FALSE(file.is_visible(0, 0));
}

TEST_P(Golden, EncoderReproducesTheCommittedBytes) {
  const Version version = GetParam();
  const urbanpvs::test::Bytes committed = urbanpvs::test::read_bytes(golden_path(version).c_str());
  ASSERT_FALSE(committed.empty());
  const rt::PvsBake bake = version.payloads() ? urbanpvs::test::golden_bake_with_payloads()
                                              : urbanpvs::test::golden_bake();
  EXPECT_EQ(rt::encode(bake, urbanpvs::test::golden_options(version.major, version.minor)),
            committed)
      << "the encoder's output changed: a format change needs a new version and a new golden "
         "file (target update-golden), and the old file must keep decoding";
}

INSTANTIATE_TEST_SUITE_P(EveryVersion, Golden,
                         ::testing::Values(Version{1, 0}, Version{2, 0}, Version{2, 1},
                                           Version{2, 2}),
                         [](const auto& p) { return p.param.name(); });

}  // namespace
