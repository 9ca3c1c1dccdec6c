// SPDX-License-Identifier: GPL-3.0-or-later
// The far field's kept answers per sample (issue 13) and the order the bake takes its cells in:
// neither may change a PVS. The far field that keeps answers is compared with one that keeps
// none, over cells taken in random order with random open sets (as the near maps would leave
// them); the horizon's query that leaves the sweep as it is gives the answers of the one that
// moves it; horizons that leave out steep sloped tops give the answers of horizons that take
// every top; sweeps that watch only their few objects' directions give what sweeps all round
// give; the objects "all but the decided" give what their list gives; the Hilbert order is a
// permutation that walks from neighbour to neighbour, and the threads walk it in stretches.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <numeric>
#include <random>
#include <thread>

#include "HillyCity.hpp"
#include "SlopedLod2City.hpp"
#include "urbanpvs/cities/CityGenerator.hpp"
#include "urbanpvs/cities/CityJsonWriter.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/preprocess/bake/BakeScene.hpp"
#include "urbanpvs/preprocess/bake/CellOrder.hpp"
#include "urbanpvs/preprocess/bake/ParallelBake.hpp"
#include "urbanpvs/preprocess/visibility/FarField.hpp"

namespace urbanpvs::preprocess {
namespace {

const BakeScene& scene() {
  static const geometry::City city = [] {
    cities::CityParams p;
    p.size_km2 = 0.1;
    p.seed = 9;
    return geometry::read_city_text(cities::cityJsonText(cities::generateCity(p)), "gen.city.json");
  }();
  static const BakeScene s(city, BakeOptions{});
  return s;
}

std::vector<std::uint32_t> sorted(std::vector<std::uint32_t> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Every object, or at random (`mixed`) a random half: another cell's near maps decide others.
std::vector<std::uint32_t> open_set(std::size_t objects, std::mt19937_64& rng, bool mixed = true) {
  std::vector<std::uint32_t> open(objects);
  std::iota(open.begin(), open.end(), 0u);
  if (mixed && rng() % 3 != 0) {
    std::shuffle(open.begin(), open.end(), rng);
    open.resize(objects / 2);
    std::sort(open.begin(), open.end());
  }
  return open;
}

TEST(FarField, KeptAnswersGiveTheSameObjectsInAnyOrderOfCells) {
  const BakeScene& s = scene();
  ASSERT_GT(s.cell_count(), 200u);
  std::vector<std::uint32_t> cells(s.cell_count());
  std::iota(cells.begin(), cells.end(), 0u);
  std::mt19937_64 rng(3);
  // Neighbours in turn with every object open (kept answers are read and spare sweeps), then
  // at random with random open sets, each cell met twice.
  constexpr std::size_t kNeighbours = 150;
  std::vector<std::uint32_t> order = along_hilbert_curve(s.mesh(), cells);
  order.resize(kNeighbours);
  std::vector<std::uint32_t> random = order;
  std::shuffle(random.begin(), random.end(), rng);
  order.insert(order.end(), random.begin(), random.end());

  FarField keeping(s), fresh(s, 0);
  CellCounters kept_counts, fresh_counts;
  std::size_t seen = 0, asked = 0, neighbour_sweeps = 0, neighbour_fresh_sweeps = 0;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t cell = order[k];
    const std::vector<Vec3> samples = s.samples(cell);
    const std::vector<std::uint32_t> open =
        open_set(s.city().objects.size(), rng, k >= kNeighbours);
    const std::vector<std::uint32_t> a = keeping.visible(samples, open, kept_counts);
    const std::vector<std::uint32_t> b = fresh.visible(samples, open, fresh_counts);
    const std::vector<std::uint32_t> sa = sorted(a);
    ASSERT_EQ(sa, sorted(b)) << "cell " << cell;
    ASSERT_TRUE(std::includes(open.begin(), open.end(), sa.begin(), sa.end()));
    seen += a.size();
    asked += open.size();
    if (k + 1 == kNeighbours) {
      neighbour_sweeps = kept_counts.sample_sweeps;
      neighbour_fresh_sweeps = fresh_counts.sample_sweeps;
    }
  }
  // Not vacuous: the far field hides some and shows some, and the kept answers spared sweeps.
  EXPECT_GT(seen, asked / 50);
  EXPECT_LT(seen, asked);
  EXPECT_EQ(fresh_counts.sweeps_spared, 0u);
  EXPECT_GT(kept_counts.sweeps_spared, 0u);
  EXPECT_LT(neighbour_sweeps, neighbour_fresh_sweeps * 3 / 4);
  EXPECT_EQ(kept_counts.sample_sweeps + kept_counts.sweeps_spared, fresh_counts.sample_sweeps);
}

TEST(FarField, FewKeptSamplesStillGiveTheSameObjects) {
  // Two slots for cells of about twenty samples: a cell reads more kept samples than there are
  // slots, and a slot it reads must never be handed to another of its samples.
  const BakeScene& s = scene();
  FarField two(s, 2), fresh(s, 0);
  CellCounters counts;
  std::mt19937_64 rng(8);
  for (std::uint32_t cell = 0; cell < 60; ++cell) {
    const std::vector<Vec3> samples = s.samples(cell);
    const std::vector<std::uint32_t> open = open_set(s.city().objects.size(), rng);
    ASSERT_EQ(sorted(two.visible(samples, open, counts)),
              sorted(fresh.visible(samples, open, counts)))
        << "cell " << cell;
  }
}

TEST(FarField, AllButTheDecidedGivesWhatTheListOfTheRestGives) {
  // The bake passes the far field the objects its maps decided, and every other one is open:
  // the same answers as the list of those others, with kept answers or without.
  const BakeScene& s = scene();
  const std::size_t objects = s.city().objects.size();
  ASSERT_NE(objects % 64, 0u) << "the last word's unused bits are not exercised";
  FarField keeping(s), fresh(s, 0);
  CellCounters all_but_counts, list_counts;
  std::mt19937_64 rng(5);
  for (std::uint32_t cell = 0; cell < 80; ++cell) {
    std::vector<std::uint32_t> shuffled(objects);
    std::iota(shuffled.begin(), shuffled.end(), 0u);
    std::shuffle(shuffled.begin(), shuffled.end(), rng);
    // None decided, a few (as near a small cell), or most.
    const std::size_t n = cell % 3 == 0 ? 0 : cell % 3 == 1 ? objects / 20 : objects * 9 / 10;
    const std::vector<std::uint32_t> decided(shuffled.begin(),
                                             shuffled.begin() + static_cast<std::ptrdiff_t>(n));
    std::vector<std::uint32_t> rest(shuffled.begin() + static_cast<std::ptrdiff_t>(n),
                                    shuffled.end());
    std::sort(rest.begin(), rest.end());
    const std::vector<Vec3> samples = s.samples(cell);
    const std::size_t before = all_but_counts.objects_far_field;
    const std::vector<std::uint32_t> a =
        sorted(keeping.visible_all_but(samples, decided, all_but_counts));
    ASSERT_EQ(all_but_counts.objects_far_field - before, rest.size()) << "cell " << cell;
    ASSERT_EQ(a, sorted(fresh.visible(samples, rest, list_counts))) << "cell " << cell;
    ASSERT_TRUE(std::includes(rest.begin(), rest.end(), a.begin(), a.end()));
  }
  EXPECT_GT(all_but_counts.sweeps_spared, 0u);
}

const BakeScene& sloped_scene() {
  static const BakeScene s(sloped_lod2_city(), BakeOptions{});
  return s;
}

TEST(FarField, SteepTopsLeftOutOfTheHorizonsGiveTheSameObjectsWithFewerWalls) {
  const BakeScene& s = sloped_scene();
  std::size_t steep = 0;
  for (const geometry::Occluder& o : s.occluders())
    if (std::hypot(o.slope.x, o.slope.y) >= 0.25) ++steep;
  ASSERT_GT(steep, s.occluders().size() / 2);
  // Without kept answers, so that both sweep every sample and the counts compare.
  FarField lean(s, 0), full(s, 0, FarField::HorizonTops::All);
  CellCounters lean_counts, full_counts;
  std::vector<std::uint32_t> cells(s.cell_count());
  std::iota(cells.begin(), cells.end(), 0u);
  std::vector<std::uint32_t> order = along_hilbert_curve(s.mesh(), cells);
  order.resize(std::min<std::size_t>(order.size(), 120));
  std::size_t seen = 0, asked = 0;
  for (std::uint32_t cell : order) {
    const std::vector<Vec3> samples = s.samples(cell);
    std::vector<std::uint32_t> open(s.city().objects.size());
    std::iota(open.begin(), open.end(), 0u);
    const std::vector<std::uint32_t> a = sorted(lean.visible(samples, open, lean_counts));
    ASSERT_EQ(a, sorted(full.visible(samples, open, full_counts))) << "cell " << cell;
    seen += a.size();
    asked += open.size();
  }
  EXPECT_GT(seen, asked / 50);
  EXPECT_LT(seen, asked);
  EXPECT_EQ(lean_counts.sample_sweeps, full_counts.sample_sweeps);
  // The walls left out: a quarter of those the full horizons add, or more.
  EXPECT_LT(lean_counts.occluders_far_field, full_counts.occluders_far_field * 3 / 4);
}

// A hilly city whose terrain occludes as sloped squares of 8 m: 0.25 km², so that the far
// field meets squares merged up to several levels.
const BakeScene& hilly_scene() {
  static const geometry::City city = generated_hilly_city(0.25, 60);
  static const BakeScene s = [] {
    BakeOptions o;
    o.blocks.terrain_planes = 8;
    return BakeScene(city, o);
  }();
  return s;
}

TEST(TerrainPyramid, EveryNodeLiesUnderTheSquaresItCoversAndEachSquareHasOneRoot) {
  const BakeScene& s = hilly_scene();
  const TerrainPyramid& pyramid = s.terrain_pyramid();
  const auto& nodes = pyramid.nodes();
  std::vector<const geometry::Occluder*> squares;
  for (std::uint32_t o = 0; o < s.occluders().size(); ++o)
    if (s.is_terrain_square(o)) squares.push_back(&s.occluders()[o]);
  ASSERT_GT(squares.size(), 1000u);
  // The leaves below each node, and the roots above each leaf.
  std::vector<std::vector<std::uint32_t>> leaves(nodes.size());
  std::vector<int> roots_above(nodes.size(), 0);
  std::uint32_t top = 0;
  for (const std::uint32_t root : pyramid.roots()) {
    std::vector<std::uint32_t> stack{root}, path;
    while (!stack.empty()) {
      const std::uint32_t k = stack.back();
      stack.pop_back();
      const TerrainPyramid::Node& n = nodes[k];
      top = std::max(top, n.level);
      if (n.level == 0) {
        ++roots_above[k];
        leaves[root].push_back(k);
      }
      for (const std::int32_t c : n.child) {
        if (n.level == 0) {
          EXPECT_EQ(c, -1);
          continue;
        }
        ASSERT_GE(c, 0);
        EXPECT_EQ(nodes[static_cast<std::size_t>(c)].level + 1, n.level);
        stack.push_back(static_cast<std::uint32_t>(c));
      }
    }
  }
  EXPECT_GE(top, 3u) << "squares merged up to 64 m at least";
  std::size_t leaf_count = 0;
  for (std::uint32_t k = 0; k < nodes.size(); ++k)
    if (nodes[k].level == 0) {
      ++leaf_count;
      EXPECT_EQ(roots_above[k], 1) << "node " << k;
    }
  EXPECT_EQ(leaf_count, squares.size());
  // Every node's top lies under each grid square below it, over that square (the test reads
  // the square's own plane at its corners and at random points), within its ground and box.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  for (std::uint32_t k = 0; k < nodes.size(); ++k) {
    const TerrainPyramid::Node& n = nodes[k];
    std::vector<std::uint32_t> below;
    std::vector<std::uint32_t> stack{k};
    while (!stack.empty()) {
      const std::uint32_t j = stack.back();
      stack.pop_back();
      if (nodes[j].level == 0) below.push_back(j);
      for (const std::int32_t c : nodes[j].child)
        if (c >= 0) stack.push_back(static_cast<std::uint32_t>(c));
    }
    ASSERT_EQ(below.size(), std::size_t{1} << (2 * n.level)) << "node " << k;
    double area = 0;
    for (const std::uint32_t j : below) {
      const geometry::Occluder& leaf = nodes[j].occluder;
      area += leaf.bounds.area();
      EXPECT_LE(leaf.top_high(), n.box.zmax);
      EXPECT_TRUE(n.occluder.bounds.overlaps(leaf.bounds));
      std::vector<Vec2> points = leaf.bounds.corners();
      for (int r = 0; r < 8; ++r)
        points.push_back({leaf.bounds.min.x + unit(rng) * (leaf.bounds.max.x - leaf.bounds.min.x),
                          leaf.bounds.min.y + unit(rng) * (leaf.bounds.max.y - leaf.bounds.min.y)});
      for (const Vec2& p : points) {
        EXPECT_LE(n.occluder.top_at(p), leaf.top_at(p) + 1e-9) << "node " << k;
        EXPECT_GE(n.occluder.top_at(p), leaf.top_at(p) - n.drop - 1e-9) << "node " << k;
      }
    }
    EXPECT_NEAR(area, n.occluder.bounds.area(), 1e-6 * area) << "the node is its squares' ground";
  }
  // A horizon takes a node from kSplitRatio sides on, and its squares nearer.
  for (const TerrainPyramid::Node& n : nodes) {
    if (n.level == 0) {
      EXPECT_FALSE(pyramid.split(n, 0));
      continue;
    }
    const double side = n.occluder.bounds.max.x - n.occluder.bounds.min.x;
    EXPECT_TRUE(pyramid.split(n, 0.99 * TerrainPyramid::kSplitRatio * side));
    EXPECT_EQ(
        pyramid.split(n, 1.01 * TerrainPyramid::kSplitRatio * side),
        n.drop > TerrainPyramid::kDropPerDistance * 1.01 * TerrainPyramid::kSplitRatio * side);
  }
}

TEST(FarField, TheTerrainPyramidGivesTheObjectsOfItsSquaresWithFewerWalls) {
  const BakeScene& s = hilly_scene();
  // Every square in both horizons: square by square, or merged with distance.
  FarField pyramid(s, 0, FarField::HorizonTops::All),
      squares(s, 0, FarField::HorizonTops::All, FarField::TerrainHorizon::Squares);
  CellCounters pyramid_counts, squares_counts;
  std::vector<std::uint32_t> cells(s.cell_count());
  std::iota(cells.begin(), cells.end(), 0u);
  std::mt19937_64 rng(11);
  std::shuffle(cells.begin(), cells.end(), rng);
  cells.resize(std::min<std::size_t>(cells.size(), 80));
  std::size_t seen = 0, asked = 0;
  for (std::uint32_t cell : cells) {
    const std::vector<Vec3> samples = s.samples(cell);
    std::vector<std::uint32_t> open(s.city().objects.size());
    std::iota(open.begin(), open.end(), 0u);
    const std::vector<std::uint32_t> a = sorted(pyramid.visible(samples, open, pyramid_counts));
    ASSERT_EQ(a, sorted(squares.visible(samples, open, squares_counts))) << "cell " << cell;
    seen += a.size();
    asked += open.size();
  }
  EXPECT_GT(seen, asked / 50);
  EXPECT_LT(seen, asked);
  EXPECT_LT(pyramid_counts.occluders_far_field, squares_counts.occluders_far_field);
  std::printf("walls: pyramid %zu, squares %zu; sight lines: pyramid %zu, squares %zu\n",
              static_cast<std::size_t>(pyramid_counts.occluders_far_field),
              static_cast<std::size_t>(squares_counts.occluders_far_field),
              static_cast<std::size_t>(pyramid_counts.sight_lines),
              static_cast<std::size_t>(squares_counts.sight_lines));
}

TEST(SampleHorizon, AskingAsIsGivesTheSweepsAnswerAndChangesNoLaterOne) {
  const BakeScene& s = scene();
  const std::vector<Vec3> samples = s.samples(s.cell_count() / 2);
  const auto& objects = s.city().objects;
  std::size_t hidden = 0;
  for (const Vec3& sample : samples) {
    // Every occluder added, then every object asked in order of distance: one horizon by
    // hides() (settling walls as the front moves), one by hides_as_is() on every other object.
    SampleHorizon moving, still;
    moving.reset(sample);
    still.reset(sample);
    for (const geometry::Occluder& o : s.occluders()) {
      moving.add(o);
      still.add(o);
    }
    std::vector<std::uint32_t> by_distance(objects.size());
    std::iota(by_distance.begin(), by_distance.end(), 0u);
    std::stable_sort(by_distance.begin(), by_distance.end(), [&](std::uint32_t a, std::uint32_t b) {
      return moving.distance_to(objects[a].bbox.xy) < moving.distance_to(objects[b].bbox.xy);
    });
    for (std::size_t k = 0; k < by_distance.size(); ++k) {
      const geometry::Box3& box = objects[by_distance[k]].bbox;
      const bool as_is = still.hides_as_is(box);
      const bool swept = moving.hides(box);
      ASSERT_EQ(as_is, swept) << "object " << by_distance[k];
      if (k % 2 == 0) {  // the still one moves now and then
        ASSERT_EQ(still.hides(box), swept);
      }
      hidden += swept ? 1 : 0;
    }
  }
  EXPECT_GT(hidden, 0u);
}

// Sweeps asked about few objects watch only their directions (SampleHorizon::watch_none): the
// same objects as sweeps all round, with fewer walls. Open sets of 1 to 40 objects (as a kept
// sample of a neighbouring cell is asked) and of all of them, on a flat generated city, on
// pitched LoD2 roofs (sloped tops, steep ones out of the horizons) and on hills whose terrain
// squares occlude (walls below the eye, the pyramid's merged squares).
void expect_watching_few_objects_changes_no_answer(const BakeScene& s, std::size_t cells) {
  const std::size_t objects = s.city().objects.size();
  ASSERT_GT(objects, 64u);
  // Without kept answers, so that both sweep every sample and the counts compare.
  FarField watching(s, 0),
      all_round(s, 0, FarField::HorizonTops::AllButSteep, FarField::TerrainHorizon::Pyramid,
                FarField::SweepWatch::AllRound);
  CellCounters watching_counts, all_round_counts;
  std::mt19937_64 rng(11);
  std::size_t seen = 0, hidden = 0;
  for (std::uint32_t cell = 0; cell < std::min<std::size_t>(cells, s.cell_count()); ++cell) {
    std::vector<std::uint32_t> open(objects);
    std::iota(open.begin(), open.end(), 0u);
    if (cell % 4 != 0) {
      std::shuffle(open.begin(), open.end(), rng);
      open.resize(1 + rng() % 40);
      std::sort(open.begin(), open.end());
    }
    const std::vector<Vec3> samples = s.samples(cell);
    const std::vector<std::uint32_t> a = sorted(watching.visible(samples, open, watching_counts));
    ASSERT_EQ(a, sorted(all_round.visible(samples, open, all_round_counts))) << "cell " << cell;
    if (open.size() < objects) {
      seen += a.size();
      hidden += open.size() - a.size();
    }
  }
  // Not vacuous: few-object sweeps found objects both seen and hidden, and they watched.
  EXPECT_GT(seen, 0u);
  EXPECT_GT(hidden, 0u);
  EXPECT_EQ(all_round_counts.narrow_sweeps, 0u);
  EXPECT_GT(watching_counts.narrow_sweeps, watching_counts.sample_sweeps / 2);
  EXPECT_EQ(watching_counts.sample_sweeps, all_round_counts.sample_sweeps);
  EXPECT_LT(watching_counts.occluders_far_field, all_round_counts.occluders_far_field * 3 / 4);
}

TEST(FarField, SweepsThatWatchTheirFewObjectsGiveTheSameObjectsWithFewerWalls) {
  expect_watching_few_objects_changes_no_answer(scene(), 160);
}

TEST(FarField, SweepsThatWatchTheirFewObjectsGiveTheSameObjectsOnPitchedRoofs) {
  expect_watching_few_objects_changes_no_answer(sloped_scene(), 120);
}

TEST(FarField, SweepsThatWatchTheirFewObjectsGiveTheSameObjectsOnHills) {
  expect_watching_few_objects_changes_no_answer(hilly_scene(), 120);
}

TEST(CellOrder, AlongTheHilbertCurveIsAPermutationThatStepsToNeighbours) {
  const geometry::ViewCellMesh& mesh = scene().mesh();
  std::vector<std::uint32_t> cells(mesh.cells.size());
  std::iota(cells.begin(), cells.end(), 0u);
  const std::vector<std::uint32_t> order = along_hilbert_curve(mesh, cells);
  EXPECT_EQ(sorted(order), cells);
  EXPECT_EQ(along_hilbert_curve(mesh, cells), order);  // deterministic

  auto mean_step = [&](const std::vector<std::uint32_t>& o) {
    double sum = 0;
    for (std::size_t k = 1; k < o.size(); ++k) {
      const auto& a = mesh.cells[o[k - 1]].corner;
      const auto& b = mesh.cells[o[k]].corner;
      sum += glm::length((a[0] + a[1] + a[2]) / 3.0 - (b[0] + b[1] + b[2]) / 3.0);
    }
    return sum / double(o.size() - 1);
  };
  std::vector<std::uint32_t> shuffled = cells;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937_64(1));
  const double hilbert = mean_step(order);
  EXPECT_LT(hilbert, mean_step(shuffled) / 10);
  EXPECT_LE(hilbert, mean_step(cells));
  EXPECT_LT(hilbert, 2 * mesh.options.max_cell_edge);

  // A subset (the cells of one bake part) keeps its own cells only.
  const std::vector<std::uint32_t> part(cells.begin() + 10, cells.begin() + 40);
  EXPECT_EQ(sorted(along_hilbert_curve(mesh, part)), part);
}

// bake_cells hands each thread a stretch of the Hilbert order and takes its chunks from the
// front, so that the thread's FarField finds its neighbours' samples kept; a thread done early
// takes half of the longest stretch left. Every cell once, the same PVS as one thread, on any
// thread count and chunk size, and each thread's cells few runs of the order (taking chunks in
// turn from one counter gave each thread every other chunk: 120 runs for chunks of one).
TEST(ParallelBake, EveryCellOnceWithTheSamePvsAndEachThreadAlongFewStretches) {
  const BakeScene& s = scene();
  std::vector<std::uint32_t> cells(std::min<std::size_t>(s.cell_count(), 240));
  std::iota(cells.begin(), cells.end(), 0u);
  const std::vector<std::uint32_t> order = along_hilbert_curve(s.mesh(), cells);
  std::vector<std::size_t> position(s.cell_count());
  for (std::size_t k = 0; k < order.size(); ++k) position[order[k]] = k;

  std::vector<std::vector<std::uint32_t>> one_thread(s.cell_count());
  bake_cells(s, cells, ParallelBakeOptions{}, [&](CellOutcome& o) { one_thread[o.cell] = o.pvs; });
  for (const unsigned threads : {2u, 3u, 5u})
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{64}}) {
      std::mutex m;
      std::vector<int> times(s.cell_count(), 0);
      std::map<std::thread::id, std::vector<std::size_t>> taken;
      ParallelBakeOptions options;
      options.threads = threads;
      options.max_chunk = chunk;
      bake_cells(s, cells, options, [&](CellOutcome& o) {
        const std::lock_guard<std::mutex> lock(m);
        ++times[o.cell];
        EXPECT_EQ(o.pvs, one_thread[o.cell]) << "cell " << o.cell;
        taken[std::this_thread::get_id()].push_back(position[o.cell]);
      });
      for (const std::uint32_t c : cells) ASSERT_EQ(times[c], 1) << "cell " << c;
      for (auto& [id, at] : taken) {
        std::sort(at.begin(), at.end());
        std::size_t runs = 1;
        for (std::size_t k = 1; k < at.size(); ++k) runs += at[k] != at[k - 1] + 1 ? 1 : 0;
        EXPECT_LE(runs, 20u) << threads << " threads, chunks of " << chunk;
      }
    }
}

}  // namespace
}  // namespace urbanpvs::preprocess
