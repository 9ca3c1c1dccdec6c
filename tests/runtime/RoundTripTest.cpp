// SPDX-License-Identifier: MIT
// encode → open → compare everything, over many random bakes and encoding options.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "RandomBake.hpp"
#include "urbanpvs/runtime/Format.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

namespace rt = urbanpvs::runtime;
using urbanpvs::test::random_mesh_bake;
using urbanpvs::test::RandomBakeOptions;

/// Opens a copy of `bytes` owned by the file (so temporaries can be passed).
rt::PvsFile open_ok(std::vector<std::byte> bytes, bool expand = false) {
  rt::PvsFile file;
  rt::LoadError error;
  rt::LoadOptions options;
  options.expand_pvs = expand;
  const rt::Status s = rt::PvsFile::open_owned(std::move(bytes), file, options, &error);
  EXPECT_EQ(s, rt::Status::kOk) << error.detail;
  return file;
}

void expect_bbox(const rt::Bbox& got, const rt::Bbox& want, bool float32) {
  for (int k = 0; k < 6; ++k) {
    if (!float32) {
      EXPECT_EQ(got[k], want[k]);
      continue;
    }
    // Rounded outwards to the next float32: never shrinks, grows by less than one float ulp.
    const double ulp = std::nextafter(static_cast<float>(std::fabs(want[k])), INFINITY) -
                       static_cast<float>(std::fabs(want[k]));
    if (k < 3) {
      EXPECT_LE(got[k], want[k]);
    } else {
      EXPECT_GE(got[k], want[k]);
    }
    EXPECT_LE(std::fabs(got[k] - want[k]), ulp);
  }
}

double cross(const rt::Point2& a, const rt::Point2& b, const rt::Point2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

/// FORMAT.md's neighbour rule of 2.x, brute force over the stored cells: across edge k of c is
/// the lowest-index other cell with both end points of the edge among its corners and its third
/// corner strictly on the other side.
std::vector<std::array<std::uint32_t, 3>> neighbours_by_rule(const rt::PvsFile& file) {
  std::vector<rt::CellGeometry> g(file.cell_count());
  for (std::uint32_t c = 0; c < file.cell_count(); ++c) file.cell(c, g[c]);
  const auto same = [](const rt::Point2& p, const rt::Point2& q) {
    return p.x == q.x && p.y == q.y;
  };
  std::vector<std::array<std::uint32_t, 3>> out(g.size(), {rt::kNoCell, rt::kNoCell, rt::kNoCell});
  for (std::uint32_t c = 0; c < g.size(); ++c) {
    for (int k = 0; k < 3; ++k) {
      const rt::Point2 a = g[c].triangle[k], b = g[c].triangle[(k + 1) % 3];
      const double side = cross(a, b, g[c].triangle[(k + 2) % 3]);
      if (same(a, b) || side == 0) continue;
      for (std::uint32_t d = 0; d < g.size() && out[c][k] == rt::kNoCell; ++d) {
        if (d == c) continue;
        int has_a = -1, has_b = -1;
        for (int j = 0; j < 3; ++j) {
          if (same(g[d].triangle[j], a)) has_a = j;
          if (same(g[d].triangle[j], b)) has_b = j;
        }
        if (has_a < 0 || has_b < 0 || has_a == has_b) continue;
        const double other = cross(a, b, g[d].triangle[3 - has_a - has_b]);
        if (other * side < 0) out[c][k] = d;
      }
    }
  }
  return out;
}

void expect_same(const rt::PvsBake& bake, const rt::PvsFile& file,
                 const rt::EncodeOptions& options = {}) {
  ASSERT_TRUE(file.is_open());
  const bool float32 = options.bbox_float32;
  const bool v1 = file.major_version() == 1;
  ASSERT_EQ(file.major_version(), options.format_major);
  // FORMAT.md: the lowest minor that holds the file: 2.2 with a coded PVS, 2.1 with payloads.
  const bool coded = !v1 && options.pvs_coding == rt::PvsCoding::kExpGolomb;
  EXPECT_EQ(file.minor_version(), coded ? 2 : bake.payload_key.empty() ? 0 : 1);
  EXPECT_EQ(file.has_payloads(), !bake.payload_key.empty());
  EXPECT_EQ(file.payload_key(), bake.payload_key);
  const auto rule = v1 ? std::vector<std::array<std::uint32_t, 3>>{} : neighbours_by_rule(file);
  const rt::FrameInfo f = file.frame();
  EXPECT_EQ(f.crs, bake.meta.frame.crs);
  EXPECT_EQ(f.geographic, bake.meta.frame.geographic);
  EXPECT_EQ(f.origin, bake.meta.frame.origin);
  EXPECT_EQ(f.geodetic_origin.lat_deg, bake.meta.frame.geodetic_origin.lat_deg);
  EXPECT_EQ(f.geodetic_origin.lon_deg, bake.meta.frame.geodetic_origin.lon_deg);
  EXPECT_EQ(f.geodetic_origin.h_m, bake.meta.frame.geodetic_origin.h_m);
  const rt::BakeSettings s = file.settings();
  EXPECT_EQ(s.epsilon_m, bake.meta.settings.epsilon_m);
  EXPECT_EQ(s.pixel_size_m, bake.meta.settings.pixel_size_m);
  EXPECT_EQ(s.max_cell_edge_m, bake.meta.settings.max_cell_edge_m);
  EXPECT_EQ(s.eye_min_m, bake.meta.settings.eye_min_m);
  EXPECT_EQ(s.eye_max_m, bake.meta.settings.eye_max_m);
  EXPECT_EQ(s.input_hash, bake.meta.settings.input_hash);
  ASSERT_EQ(file.property_count(), bake.meta.properties.size());
  for (std::size_t i = 0; i < file.property_count(); ++i) {
    std::string_view k, v;
    ASSERT_EQ(file.property(i, k, v), rt::Status::kOk);
    EXPECT_EQ(k, bake.meta.properties[i].first);
    EXPECT_EQ(v, bake.meta.properties[i].second);
  }
  ASSERT_EQ(file.object_count(), bake.objects.size());
  for (std::uint32_t i = 0; i < file.object_count(); ++i) {
    rt::ObjectInfo o;
    ASSERT_EQ(file.object(i, o), rt::Status::kOk);
    EXPECT_EQ(o.source_id, bake.objects[i].source_id);
    EXPECT_EQ(o.payload, bake.objects[i].payload);
    expect_bbox(o.bbox, bake.objects[i].bbox, float32);
  }
  ASSERT_EQ(file.cell_count(), bake.cells.size());
  std::vector<std::uint32_t> buffer(file.decode_buffer_size());
  rt::PvsDecoder decoder(file);
  std::uint64_t total = 0;
  for (std::uint32_t c = 0; c < file.cell_count(); ++c) {
    const rt::CellRecord& want = bake.cells[c];
    rt::CellGeometry g;
    ASSERT_EQ(file.cell(c, g), rt::Status::kOk);
    if (v1) {  // float64, bit for bit
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(g.triangle[k].x, want.triangle[k].x);
        EXPECT_EQ(g.triangle[k].y, want.triangle[k].y);
      }
      EXPECT_EQ(g.z_min, want.z_min);
      EXPECT_EQ(g.z_max, want.z_max);
      EXPECT_EQ(g.neighbours, want.neighbours);
    } else {  // whole millimetres, z rounded outwards; neighbours by the rule
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(g.triangle[k].x, std::nearbyint(want.triangle[k].x / 0.001) * 0.001);
        EXPECT_EQ(g.triangle[k].y, std::nearbyint(want.triangle[k].y / 0.001) * 0.001);
      }
      EXPECT_LE(g.z_min, want.z_min);
      EXPECT_GT(g.z_min, want.z_min - 0.001);
      EXPECT_GE(g.z_max, want.z_max);
      EXPECT_LT(g.z_max, want.z_max + 0.001);
      EXPECT_EQ(g.neighbours, rule[c]) << "cell " << c;
    }
    std::size_t n = 0;
    ASSERT_EQ(file.decode_pvs(c, buffer.data(), buffer.size(), n), rt::Status::kOk);
    ASSERT_EQ(std::vector<std::uint32_t>(buffer.begin(), buffer.begin() + n), want.pvs)
        << "cell " << c;
    ASSERT_EQ(decoder.decode(c), rt::Status::kOk);
    EXPECT_EQ(std::vector<std::uint32_t>(decoder.begin(), decoder.end()), want.pvs);
    EXPECT_EQ(file.pvs_size(c), want.pvs.size());
    total += want.pvs.size();
  }
  EXPECT_EQ(file.total_pvs_entries(), total);
}

/// is_visible agrees with the decoded lists for every (cell, object) pair.
void expect_visibility_matches(const rt::PvsBake& bake, const rt::PvsFile& file) {
  for (std::uint32_t c = 0; c < bake.cells.size(); ++c) {
    std::vector<char> in(bake.objects.size() + 1, 0);
    for (std::uint32_t o : bake.cells[c].pvs) in[o] = 1;
    for (std::uint32_t o = 0; o <= bake.objects.size(); ++o) {
      ASSERT_EQ(file.is_visible(c, o), in[o] != 0) << "cell " << c << " object " << o;
    }
  }
}

struct Variant {
  rt::EncodeOptions encode;
  RandomBakeOptions bake;
};

std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (std::uint32_t chain : {0u, 1u, 2u, 4u}) {
    for (double threshold : {0.7, 1.0}) {
      Variant v;
      v.encode.max_diff_chain = chain;
      v.encode.diff_threshold = threshold;
      v.encode.bbox_float32 = chain % 2 == 0;
      out.push_back(v);
    }
  }
  Variant dense;  // bitsets
  dense.bake.density = 0.85;
  out.push_back(dense);
  Variant sparse_large;  // large indices, few visible
  sparse_large.bake.objects = 70000;
  sparse_large.bake.min_object = 69000;
  sparse_large.bake.density = 0.05;
  out.push_back(sparse_large);
  Variant no_neighbours;  // coherence found through the previous cell only
  no_neighbours.bake.neighbours = false;
  no_neighbours.encode.max_diff_chain = 4;
  out.push_back(no_neighbours);
  Variant incoherent;
  incoherent.bake.coherence = 0.2;
  out.push_back(incoherent);
  Variant payloads;  // 2.1
  payloads.bake.payloads = true;
  out.push_back(payloads);
  return out;
}

TEST(RoundTrip, RandomBakesManySeedsAndOptions) {
  std::vector<Variant> all = variants();
  for (std::size_t v = 0, n = all.size(); v < n; ++v) {  // every variant in every version:
    all.push_back(all[v]);                               // 2.0/2.1 (varint coded)
    all.back().encode.pvs_coding = rt::PvsCoding::kVarint;
    if (all[v].bake.payloads) continue;  // (payloads need 2.1)
    all.push_back(all[v]);
    all.back().encode.format_major = 1;
  }
  for (std::size_t v = 0; v < all.size(); ++v) {
    for (std::uint64_t seed = 0; seed < 12; ++seed) {
      SCOPED_TRACE("variant " + std::to_string(v) + " seed " + std::to_string(seed));
      RandomBakeOptions o = all[v].bake;
      o.nx = 1 + static_cast<std::uint32_t>(seed % 5);
      o.ny = 1 + static_cast<std::uint32_t>((seed * 7) % 6);
      const rt::PvsBake bake = random_mesh_bake(seed * 131 + v, o);
      const auto bytes = rt::encode(bake, all[v].encode);
      EXPECT_EQ(bytes, rt::encode(bake, all[v].encode)) << "encode is not deterministic";
      for (const bool expand : {false, true}) {  // decoded, and from the expanded records
        const rt::PvsFile file = open_ok(bytes, expand);
        ASSERT_EQ(file.is_expanded(), expand);
        expect_same(bake, file, all[v].encode);
        if (bake.objects.size() < 1000) expect_visibility_matches(bake, file);
        ASSERT_FALSE(HasFailure());
      }
    }
  }
}

TEST(RoundTrip, DiffChainsStayWithinTheBound) {
  RandomBakeOptions o;
  o.nx = 12;
  o.ny = 12;
  o.coherence = 0.97;
  const rt::PvsBake bake = random_mesh_bake(99, o);
  for (std::uint32_t chain : {0u, 1u, 2u, 3u, 4u, 9u}) {
    rt::EncodeOptions e;
    e.max_diff_chain = chain;
    e.diff_threshold = 1.0;
    const rt::PvsFile file = open_ok(rt::encode(bake, e));
    std::uint32_t longest = 0;
    for (std::uint32_t c = 0; c < file.cell_count(); ++c) {
      rt::PvsEncodingInfo info;
      ASSERT_EQ(file.pvs_encoding(c, info), rt::Status::kOk);
      longest = std::max(longest, info.chain_length);
    }
    EXPECT_EQ(longest, std::min(chain, rt::format::kMaxDiffChain));
    EXPECT_EQ(file.decode_buffer_size(),
              (longest >= 2 ? 2u : 1u) * std::max<std::size_t>(file.max_pvs_size(), 1));
    expect_same(bake, file, e);
  }
}

TEST(RoundTrip, Version2DerivesTheNeighboursOfAMesh) {
  RandomBakeOptions o;
  o.nx = 9;
  o.ny = 7;
  const rt::PvsBake bake = random_mesh_bake(12, o);
  const rt::PvsFile file = open_ok(rt::encode(bake));
  ASSERT_EQ(file.major_version(), 2);
  std::size_t inner = 0;
  for (std::uint32_t c = 0; c < file.cell_count(); ++c) {
    rt::CellGeometry g;
    ASSERT_EQ(file.cell(c, g), rt::Status::kOk);
    EXPECT_EQ(g.neighbours, bake.cells[c].neighbours) << "cell " << c;
    for (std::uint32_t n : g.neighbours) inner += n != rt::kNoCell;
  }
  EXPECT_GT(inner, file.cell_count());  // most edges are shared
}

TEST(RoundTrip, StackedCellsAreNotNeighboursOfEachOther) {
  rt::PvsBake bake;
  bake.objects.resize(2, {"o", {0, 0, 0, 1, 1, 1}, {}});
  rt::CellRecord cell;
  cell.triangle = {rt::Point2{0, 0}, {4, 0}, {0, 4}};
  cell.z_max = 2;
  bake.cells.push_back(cell);
  cell.z_min = 3;  // the same triangle one level up
  cell.z_max = 5;
  bake.cells.push_back(cell);
  cell.triangle = {rt::Point2{4, 0}, {4, 4}, {0, 4}};  // across the diagonal
  bake.cells.push_back(cell);
  const rt::PvsFile file = open_ok(rt::encode(bake));
  rt::CellGeometry g;
  ASSERT_EQ(file.cell(0, g), rt::Status::kOk);
  EXPECT_EQ(g.neighbours, (std::array<std::uint32_t, 3>{rt::kNoCell, 2, rt::kNoCell}));
  ASSERT_EQ(file.cell(2, g), rt::Status::kOk);
  EXPECT_EQ(g.neighbours, (std::array<std::uint32_t, 3>{rt::kNoCell, rt::kNoCell, 0}));
  EXPECT_EQ(file.locate(1, 1, 4), 1u);
  EXPECT_EQ(file.locate(1, 1, 1), 0u);
}

TEST(RoundTrip, EmptyBake) {
  const rt::PvsBake bake;
  const rt::PvsFile file = open_ok(rt::encode(bake));
  expect_same(bake, file);
  EXPECT_EQ(file.locate(0, 0, 0), rt::kNoCell);
  EXPECT_EQ(file.max_pvs_size(), 0u);
  std::uint32_t slot = 0;
  std::size_t n = 0;
  EXPECT_EQ(file.decode_pvs(0, &slot, 1, n), rt::Status::kOutOfRange);
}

TEST(RoundTrip, SingleCellEmptyAndFullPvs) {
  for (const rt::PvsCoding coding : {rt::PvsCoding::kVarint, rt::PvsCoding::kExpGolomb}) {
    for (bool full : {false, true}) {
      rt::PvsBake bake;
      bake.objects.resize(70, {"o", {0, 0, 0, 1, 1, 1}, {}});
      rt::CellRecord cell;
      cell.triangle = {rt::Point2{0, 0}, {5, 0}, {0, 5}};
      cell.z_min = 0;
      cell.z_max = 2;
      if (full) {
        for (std::uint32_t i = 0; i < 70; ++i) cell.pvs.push_back(i);
      }
      bake.cells.push_back(cell);
      rt::EncodeOptions options;
      options.pvs_coding = coding;
      const rt::PvsFile file = open_ok(rt::encode(bake, options));
      expect_same(bake, file, options);
      EXPECT_EQ(file.locate(1, 1, 1), 0u);
      rt::PvsEncodingInfo info;
      ASSERT_EQ(file.pvs_encoding(0, info), rt::Status::kOk);
      // All 70: a bitset of 13 bytes beats 70 one-byte varint gaps (72 bytes), and is kept
      // over 70 one-bit exp-Golomb codes of order 0 (kind, count, 9 bytes: 11) because it is
      // within the writer's margin of 1.25 (it decodes bytes, not bits).
      EXPECT_EQ(info.kind, static_cast<std::uint8_t>(full ? rt::format::PvsKind::kBitset
                                                          : rt::format::PvsKind::kDeltaList));
      EXPECT_EQ(info.payload_bytes, full ? 13u : 2u);
    }
  }
}

TEST(RoundTrip, ExtremeObjectIndices) {
  rt::PvsBake bake;
  bake.objects.resize(1u << 18, {"", {0, 0, 0, 0, 0, 0}, {}});
  rt::CellRecord cell;
  cell.triangle = {rt::Point2{0, 0}, {1, 0}, {0, 1}};
  cell.pvs = {0, 1, (1u << 17), (1u << 18) - 2, (1u << 18) - 1};
  bake.cells.push_back(cell);
  cell.pvs = {(1u << 18) - 1};
  bake.cells.push_back(cell);
  const rt::PvsFile file = open_ok(rt::encode(bake));
  expect_same(bake, file);
  EXPECT_TRUE(file.is_visible(0, (1u << 18) - 1));
  EXPECT_FALSE(file.is_visible(1, 0));
}

TEST(RoundTrip, OwningOpenAndMove) {
  const rt::PvsBake bake = random_mesh_bake(5, {});
  std::vector<std::byte> bytes = rt::encode(bake);
  rt::PvsFile file;
  ASSERT_EQ(rt::PvsFile::open_owned(std::move(bytes), file), rt::Status::kOk);
  rt::PvsFile moved = std::move(file);
  EXPECT_FALSE(file.is_open());  // NOLINT(bugprone-use-after-move): documented state
  expect_same(bake, moved);
}

}  // namespace
