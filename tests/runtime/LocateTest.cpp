// SPDX-License-Identifier: MIT
// locate() against a brute-force search over all cells, on meshes (with points exactly on
// shared edges and vertices) and on overlapping triangle soups.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <tuple>

#include "RandomBake.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"

namespace {

namespace rt = urbanpvs::runtime;

/// The specification of locate(): the lowest-index cell whose closed triangle contains (x, y)
/// and whose z range contains z.
std::uint32_t brute_force(const rt::PvsBake& bake, double x, double y, double z, bool check_z) {
  for (std::uint32_t c = 0; c < bake.cells.size(); ++c) {
    const rt::CellRecord& cell = bake.cells[c];
    if (check_z && !(z >= cell.z_min && z <= cell.z_max)) continue;
    if (rt::triangle_contains(cell.triangle, x, y)) return c;
  }
  return rt::kNoCell;
}

/// `bake` with the cells as the file stores them: 2.x rounds vertices to millimetres and z ranges
/// outwards, and locate() answers for the stored cells (FORMAT.md).
rt::PvsBake stored(rt::PvsBake bake, const rt::PvsFile& file) {
  for (std::uint32_t c = 0; c < bake.cells.size(); ++c) {
    rt::CellGeometry g;
    EXPECT_EQ(file.cell(c, g), rt::Status::kOk);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::fabs(g.triangle[k].x - bake.cells[c].triangle[k].x), 0.0005);
      EXPECT_LE(std::fabs(g.triangle[k].y - bake.cells[c].triangle[k].y), 0.0005);
    }
    EXPECT_LE(g.z_min, bake.cells[c].z_min);
    EXPECT_GE(g.z_max, bake.cells[c].z_max);
    bake.cells[c].triangle = g.triangle;
    bake.cells[c].z_min = g.z_min;
    bake.cells[c].z_max = g.z_max;
  }
  return bake;
}

/// A jittered mesh of 24 x 17 squares of 7.5 m (cells about 5 m across).
urbanpvs::test::RandomBakeOptions mesh_options() {
  urbanpvs::test::RandomBakeOptions o;
  o.nx = 24;
  o.ny = 17;
  o.square = 7.5;
  o.objects = 10;
  return o;
}

/// A format version, and whether the file is loaded with its PVSs expanded: locate() then reads
/// the shapes from the expanded records instead of the cell table (LocateIndex.hpp).
using Params = std::tuple<std::uint16_t, bool>;

class Locate : public ::testing::TestWithParam<Params> {
 protected:
  rt::EncodeOptions options() const {
    rt::EncodeOptions e;
    e.format_major = std::get<0>(GetParam());
    return e;
  }
  rt::PvsFile open(const std::vector<std::byte>& bytes) const {
    rt::LoadOptions load;
    load.expand_pvs = std::get<1>(GetParam());
    rt::PvsFile file;
    EXPECT_EQ(rt::PvsFile::open(bytes.data(), bytes.size(), file, load), rt::Status::kOk);
    EXPECT_EQ(file.is_expanded(), load.expand_pvs);
    return file;
  }
};

TEST_P(Locate, MeshAgreesWithBruteForceIncludingEdgesAndVertices) {
  const urbanpvs::test::RandomBakeOptions o = mesh_options();
  const auto bytes = rt::encode(urbanpvs::test::random_mesh_bake(2024, o), options());
  const rt::PvsFile file = open(bytes);
  const rt::PvsBake bake = stored(urbanpvs::test::random_mesh_bake(2024, o), file);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1), x(-5, o.nx * o.square + 5),
      y(-5, o.ny * o.square + 5), z(-2, 6), t(0.01, 0.99);
  std::size_t on_edges = 0, inside = 0;
  for (int i = 0; i < 100000; ++i) {
    double px, py;
    const rt::CellRecord& c = bake.cells[rng() % bake.cells.size()];
    const int k = static_cast<int>(rng() % 3);
    switch (i % 4) {
      case 0:
      case 1:  // anywhere, including outside the mesh
        px = x(rng);
        py = y(rng);
        break;
      case 2: {  // on an edge (as close as floating point gets)
        const double s = t(rng);
        const rt::Point2 a = c.triangle[k], b = c.triangle[(k + 1) % 3];
        px = a.x + s * (b.x - a.x);
        py = a.y + s * (b.y - a.y);
        ++on_edges;
        break;
      }
      default:  // exactly on a vertex
        px = c.triangle[k].x;
        py = c.triangle[k].y;
    }
    const double pz = (i % 8 < 6) ? c.z_min + u(rng) * (c.z_max - c.z_min) : z(rng);
    const std::uint32_t want = brute_force(bake, px, py, pz, true);
    ASSERT_EQ(file.locate(px, py, pz), want) << px << " " << py << " " << pz;
    ASSERT_EQ(file.locate(px, py, pz), want);  // deterministic
    const std::uint32_t want_xy = brute_force(bake, px, py, 0, false);
    ASSERT_EQ(file.locate_xy(px, py), want_xy);
    if (i % 4 >= 2) {
      // Points on edges and vertices of the mesh are never lost between cells.
      ASSERT_NE(want_xy, rt::kNoCell) << px << " " << py;
      ++inside;
    }
  }
  EXPECT_GT(on_edges, 20000u);
  EXPECT_GT(inside, 40000u);
}

TEST_P(Locate, OverlappingSoupReturnsLowestIndex) {
  const rt::PvsBake soup = urbanpvs::test::random_soup_bake(77, 400, 200);
  rt::EncodeOptions fine = options(), coarse = options();
  fine.grid_cells_per_cell = 4;
  coarse.grid_cells_per_cell = 0.05;
  for (const auto& e : {fine, coarse}) {
    const auto bytes = rt::encode(soup, e);
    const rt::PvsFile file = open(bytes);
    const rt::PvsBake bake = stored(soup, file);
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> p(-30, 230), z(-6, 10);
    for (int i = 0; i < 20000; ++i) {
      const double px = p(rng), py = p(rng), pz = z(rng);
      ASSERT_EQ(file.locate(px, py, pz), brute_force(bake, px, py, pz, true));
    }
  }
}

TEST_P(Locate, NonFiniteAndFarPointsAreOutside) {
  const rt::PvsBake bake = urbanpvs::test::random_mesh_bake(3, {});
  const auto bytes = rt::encode(bake, options());
  const rt::PvsFile file = open(bytes);
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const rt::CellRecord& c = bake.cells[0];
  const double cx = (c.triangle[0].x + c.triangle[1].x + c.triangle[2].x) / 3;
  const double cy = (c.triangle[0].y + c.triangle[1].y + c.triangle[2].y) / 3;
  EXPECT_NE(file.locate(cx, cy, c.z_min), rt::kNoCell);
  EXPECT_EQ(file.locate(cx, cy, c.z_max + 0.01), rt::kNoCell);  // above the prism
  EXPECT_EQ(file.locate(nan, cy, c.z_min), rt::kNoCell);
  EXPECT_EQ(file.locate(cx, nan, c.z_min), rt::kNoCell);
  EXPECT_EQ(file.locate(cx, cy, nan), rt::kNoCell);
  EXPECT_EQ(file.locate(inf, cy, c.z_min), rt::kNoCell);
  EXPECT_EQ(file.locate(-1e300, 1e300, 0), rt::kNoCell);
  EXPECT_NE(file.locate_xy(cx, cy), rt::kNoCell);
  EXPECT_EQ(file.locate_xy(cx, nan), rt::kNoCell);
}

/// The contract of locate_from() for one point and hint: a cell whose prism holds the point
/// (none only when none does), the hint when it holds it, else the first neighbour that does,
/// else locate()'s answer.
void expect_located_from(const rt::PvsFile& file, const rt::PvsBake& bake, std::uint32_t hint,
                         double x, double y, double z) {
  const std::uint32_t got = file.locate_from(hint, x, y, z);
  auto holds = [&](std::uint32_t c) {
    const rt::CellRecord& cell = bake.cells[c];
    return z >= cell.z_min && z <= cell.z_max && rt::triangle_contains(cell.triangle, x, y);
  };
  std::uint32_t want = rt::kNoCell;
  if (hint < bake.cells.size()) {
    if (holds(hint)) {
      want = hint;
    } else {
      rt::CellGeometry g;
      ASSERT_EQ(file.cell(hint, g), rt::Status::kOk);
      for (const std::uint32_t n : g.neighbours)
        if (want == rt::kNoCell && n != rt::kNoCell && holds(n)) want = n;
    }
  }
  if (want == rt::kNoCell) want = brute_force(bake, x, y, z, true);
  ASSERT_EQ(got, want) << "hint " << hint << " at " << x << " " << y << " " << z;
  if (got != rt::kNoCell) {
    ASSERT_TRUE(holds(got));
  }
}

TEST_P(Locate, FromAHintKeepsTheHintThenTriesItsNeighboursThenTheGrid) {
  const urbanpvs::test::RandomBakeOptions o = mesh_options();
  const auto bytes = rt::encode(urbanpvs::test::random_mesh_bake(2025, o), options());
  const rt::PvsFile file = open(bytes);
  const rt::PvsBake bake = stored(urbanpvs::test::random_mesh_bake(2025, o), file);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1), step(-1.5, 1.5), t(0.01, 0.99);
  // A walker that takes steps of up to 1.5 m in x and y (cells are about 5 m across: it stays,
  // crosses into a neighbour or beyond it), now and then jumps onto an edge or a vertex or out
  // of its z range, and is sometimes given another hint than its last cell.
  double x = 0.5 * o.nx * o.square, y = 0.5 * o.ny * o.square;
  std::uint32_t last = file.locate_xy(x, y);
  std::size_t kept = 0, moved = 0;
  for (int i = 0; i < 60000; ++i) {
    const rt::CellRecord& c = bake.cells[rng() % bake.cells.size()];
    const int k = static_cast<int>(rng() % 3);
    const rt::Point2 a = c.triangle[k], b = c.triangle[(k + 1) % 3];
    if (i % 50 == 0) {  // onto an edge
      const double s = t(rng);
      x = a.x + s * (b.x - a.x);
      y = a.y + s * (b.y - a.y);
    } else if (i % 50 == 1) {  // onto a vertex
      x = a.x;
      y = a.y;
    } else {
      x += step(rng);
      y += step(rng);
    }
    // Mostly at eye height over the ground at (x, y) (the cells' z bands differ), sometimes in
    // the band of the last cell or anywhere.
    const std::uint32_t under = brute_force(bake, x, y, 0, false);
    const std::uint32_t band = i % 7 == 0 ? last : under;
    const double z =
        (i % 13 == 0 || band >= bake.cells.size())
            ? -1.0 + 8 * u(rng)
            : bake.cells[band].z_min + u(rng) * (bake.cells[band].z_max - bake.cells[band].z_min);
    std::uint32_t hint = last;
    if (i % 17 == 0) hint = static_cast<std::uint32_t>(rng() % bake.cells.size());
    if (i % 19 == 0) hint = rt::kNoCell;
    if (i % 23 == 0) hint = static_cast<std::uint32_t>(bake.cells.size() + 3);
    ASSERT_NO_FATAL_FAILURE(expect_located_from(file, bake, hint, x, y, z));
    const std::uint32_t got = file.locate_from(hint, x, y, z);
    kept += got != rt::kNoCell && got == hint;
    moved += got != rt::kNoCell && got != hint && hint < bake.cells.size();
    if (got != rt::kNoCell) last = got;
    if (x < -5 || y < -5 || x > o.nx * o.square + 5 || y > o.ny * o.square + 5) {
      x = 0.5 * o.nx * o.square;
      y = 0.5 * o.ny * o.square;
      last = file.locate_xy(x, y);
    }
  }
  // Both branches are taken often: staying in the cell and leaving it.
  EXPECT_GT(kept, 10000u);
  EXPECT_GT(moved, 10000u);
  // Overlapping cells: the answer is still a cell that holds the point.
  const rt::PvsBake soup = urbanpvs::test::random_soup_bake(78, 300, 150);
  const auto soup_bytes = rt::encode(soup, options());
  const rt::PvsFile soup_file = open(soup_bytes);
  const rt::PvsBake stored_soup = stored(soup, soup_file);
  std::uniform_real_distribution<double> p(-30, 180), pz(-6, 10);
  for (int i = 0; i < 20000; ++i) {
    const auto hint = static_cast<std::uint32_t>(rng() % (soup.cells.size() + 1));
    ASSERT_NO_FATAL_FAILURE(expect_located_from(soup_file, stored_soup,
                                                hint == soup.cells.size() ? rt::kNoCell : hint,
                                                p(rng), p(rng), pz(rng)));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(file.locate_from(0, nan, 1, 0.5), rt::kNoCell);
  EXPECT_EQ(file.locate_from(0, 1, 1, nan), rt::kNoCell);
  EXPECT_EQ(rt::PvsFile().locate_from(0, 1, 1, 0.5), rt::kNoCell);
}

INSTANTIATE_TEST_SUITE_P(EveryVersion, Locate,
                         ::testing::Combine(::testing::Values(std::uint16_t{1}, std::uint16_t{2}),
                                            ::testing::Bool()),
                         [](const auto& p) {
                           return "v" + std::to_string(std::get<0>(p.param)) +
                                  (std::get<1>(p.param) ? "_expanded" : "");
                         });

}  // namespace
