// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/explain/ExcessBreakdown.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "urbanpvs/geometry/ParallelFor.hpp"
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"
#include "urbanpvs/preprocess/visibility/CellVisibility.hpp"
#include "urbanpvs/validate/RayScene.hpp"

namespace urbanpvs::explain {
namespace {

using validate::Vec3;

// Step 2's points of a cell's prism. Corners and edges are pulled 1 mm towards the centroid:
// a corner of a cell lies on a building's wall, and a viewpoint in the wall's plane would look
// along it.
std::vector<Vec3> cell_points(const runtime::CellGeometry& c, std::size_t random,
                              std::uint32_t cell, const validate::RayScene& scene, double eye_min) {
  const auto& t = c.triangle;
  const double cx = (t[0].x + t[1].x + t[2].x) / 3, cy = (t[0].y + t[1].y + t[2].y) / 3;
  auto inward = [&](double x, double y, double z) {
    const double d = std::hypot(x - cx, y - cy);
    const double f = d > 1e-3 ? 1e-3 / d : 0;
    return Vec3{x + f * (cx - x), y + f * (cy - y), z};
  };
  std::vector<Vec3> out;
  for (int k = 0; k < 3; ++k) {
    out.push_back(inward(t[k].x, t[k].y, c.z_max));
    const auto& n = t[(k + 1) % 3];
    out.push_back(inward(0.5 * (t[k].x + n.x), 0.5 * (t[k].y + n.y), c.z_max));
  }
  out.push_back({cx, cy, validate::lowest_viewpoint(c, scene, eye_min, {cx, cy})});
  // Random points, as the validator draws its viewpoints (the top face for even ones, the
  // prism for odd ones), seeded by the cell: the same cell tries the same points.
  std::mt19937_64 rng(0x9e3779b97f4a7c15ULL ^ cell);
  for (std::size_t i = 0; i < random; ++i)
    out.push_back(validate::random_viewpoint(c, i % 2 == 0, scene, eye_min, rng));
  return out;
}

bool seen_from(const validate::RayScene& scene, const Vec3& v, const std::vector<Vec3>& targets,
               std::uint32_t object, double crack) {
  return validate::first_target_seen(scene, v, targets, object, crack) != nullptr;
}

// The runs of equal objects in `items` (sorted by object first): [begin, end) index pairs, so
// that an object's targets are made once for all its items.
template <typename Item, typename ObjectOf>
std::vector<std::pair<std::size_t, std::size_t>> runs_by_object(const std::vector<Item>& items,
                                                                ObjectOf object_of) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t i = 0; i < items.size();) {
    std::size_t j = i + 1;
    while (j < items.size() && object_of(items[j]) == object_of(items[i])) ++j;
    runs.emplace_back(i, j);
    i = j;
  }
  return runs;
}

// A cell of the file and of a rebuilt scene are the same cell when their corners agree to the
// file's millimetre quantization (format 2.2 stores vertices in mm).
void check_same_cells(const preprocess::BakeScene& scene, const runtime::PvsFile& pvs) {
  if (scene.cell_count() != pvs.cell_count())
    throw std::runtime_error("the file has " + std::to_string(pvs.cell_count()) +
                             " cells, its settings give " + std::to_string(scene.cell_count()) +
                             " (another region, version or city?)");
  for (std::uint32_t i = 0; i < pvs.cell_count(); ++i) {
    runtime::CellGeometry g;
    pvs.cell(i, g);
    const geometry::ViewCell& c = scene.mesh().cells[i];
    for (int k = 0; k < 3; ++k)
      if (std::abs(g.triangle[k].x - c.corner[k].x) > 2e-3 ||
          std::abs(g.triangle[k].y - c.corner[k].y) > 2e-3)
        throw std::runtime_error("cell " + std::to_string(i) +
                                 " of the file is not the cell its settings give");
  }
}

using geometry::parallel_for;

// The PVS of each of `cells` baked with `options`, one CellVisibility per thread (each owns
// its renderer). `check` sees the scene first.
std::vector<std::vector<std::uint32_t>> bake_cells(
    const geometry::City& city, const preprocess::BakeOptions& options,
    const std::vector<std::uint32_t>& cells, unsigned threads,
    const std::function<void(const preprocess::BakeScene&)>& check = {}) {
  const preprocess::BakeScene scene(city, options, threads);
  if (check) check(scene);
  std::vector<std::unique_ptr<preprocess::CellVisibility>> visibility(threads);
  std::vector<std::vector<std::uint32_t>> out(cells.size());
  parallel_for(cells.size(), threads, [&](unsigned t, std::size_t i) {
    if (!visibility[t]) visibility[t] = std::make_unique<preprocess::CellVisibility>(scene);
    out[i] = visibility[t]->pvs(cells[i]);
  });
  return out;
}

}  // namespace

const char* cause_name(ExcessCause cause) {
  switch (cause) {
    case ExcessCause::SeenFiner:
      return "seen-finer";
    case ExcessCause::ElsewhereInCell:
      return "elsewhere-in-cell";
    case ExcessCause::Epsilon:
      return "epsilon";
    case ExcessCause::Pixel:
      return "pixel";
    case ExcessCause::FarField:
      return "far-field";
    case ExcessCause::OccluderModel:
      break;
  }
  return "occluder-model";
}

void ExplainOptions::validate() const {
  validation.validate();
  if (!(finer_spacing >= 0.01 && finer_spacing <= 1))
    throw std::invalid_argument("finer spacing must be 0.01 .. 1");
  if (cell_viewpoints > 4096) throw std::invalid_argument("cell viewpoints must be 0 .. 4096");
  if (pixel_divisor < 1 || pixel_divisor > 16)
    throw std::invalid_argument("pixel divisor must be 1 .. 16");
}

double ExcessBreakdown::tightness_without(ExcessCause cause) const {
  const auto n = static_cast<double>(counts[static_cast<std::size_t>(cause)]);
  const auto pvs = static_cast<double>(validation.pvs_total);
  const auto seen = static_cast<double>(validation.seen_total);
  if (seen == 0) return 0;
  return cause == ExcessCause::SeenFiner ? pvs / (seen + n) : (pvs - n) / seen;
}

preprocess::BakeOptions bake_options_of(const runtime::PvsFile& pvs) {
  std::vector<std::pair<std::string, std::string>> properties;
  for (std::size_t i = 0; i < pvs.property_count(); ++i) {
    std::string_view key, value;
    pvs.property(i, key, value);
    properties.emplace_back(std::string(key), std::string(value));
  }
  return preprocess::bake_options_from_properties(properties);
}

ExcessBreakdown explain_excess(const geometry::City& city, const runtime::PvsFile& pvs,
                               const preprocess::BakeOptions& bake, const ExplainOptions& options) {
  options.validate();
  ExcessBreakdown out;
  // The validator's own pass: its tightness viewpoints and what each saw.
  out.validation =
      validate::validate(city, pvs, options.validation, [&](const validate::TightnessViewpoint& t) {
        const std::size_t index = out.viewpoints.size();
        std::size_t seen = 0;
        for (const std::uint32_t o : t.pvs)
          if (!t.seen[o])
            out.objects.push_back({index, t.cell, t.viewpoint, o, ExcessCause::OccluderModel});
        for (const char s : t.seen) seen += s != 0;
        out.viewpoints.push_back({t.cell, t.pvs.size(), seen});
      });

  // Steps 1 and 2: ray casting in the input's surfaces (the validator's ground truth), one
  // RayScene per thread.
  const unsigned threads = std::max(1u, options.threads);
  std::vector<std::unique_ptr<validate::RayScene>> scenes(threads);
  auto scene_of = [&](unsigned t) -> const validate::RayScene& {
    if (!scenes[t]) scenes[t] = std::make_unique<validate::RayScene>(city);
    return *scenes[t];
  };
  const double crack = options.validation.crack;
  const double spacing = options.validation.point_spacing;
  // Step 1, by object: its finer targets are made once for all the viewpoints that kept it.
  std::vector<std::size_t> by_object(out.objects.size());
  for (std::size_t i = 0; i < by_object.size(); ++i) by_object[i] = i;
  std::stable_sort(by_object.begin(), by_object.end(), [&](std::size_t a, std::size_t b) {
    return out.objects[a].object < out.objects[b].object;
  });
  const auto object_runs =
      runs_by_object(by_object, [&](std::size_t i) { return out.objects[i].object; });
  parallel_for(object_runs.size(), threads, [&](unsigned t, std::size_t r) {
    const auto [begin, end] = object_runs[r];
    const std::uint32_t object = out.objects[by_object[begin]].object;
    const auto finer =
        validate::target_points(city.objects[object], spacing * options.finer_spacing);
    for (std::size_t k = begin; k < end; ++k) {
      ExcessObject& e = out.objects[by_object[k]];
      if (seen_from(scene_of(t), e.at, finer, object, crack)) e.cause = ExcessCause::SeenFiner;
    }
  });
  // Step 2 once per (cell, object), however many viewpoints of the cell had it; by object too.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (object, cell)
  for (const ExcessObject& e : out.objects)
    if (e.cause != ExcessCause::SeenFiner) pairs.emplace_back(e.object, e.cell);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<char> seen_in_cell(pairs.size(), 0);
  const auto pair_runs = runs_by_object(pairs, [](const auto& p) { return p.first; });
  parallel_for(pair_runs.size(), threads, [&](unsigned t, std::size_t r) {
    const auto [begin, end] = pair_runs[r];
    const std::uint32_t object = pairs[begin].first;
    const auto aims = validate::target_points(city.objects[object], spacing);
    for (std::size_t k = begin; k < end; ++k) {
      runtime::CellGeometry g;
      pvs.cell(pairs[k].second, g);
      for (const Vec3& p : cell_points(g, options.cell_viewpoints, pairs[k].second, scene_of(t),
                                       pvs.settings().eye_min_m))
        if (seen_from(scene_of(t), p, aims, object, crack)) {
          seen_in_cell[k] = 1;
          break;
        }
    }
  });
  std::vector<ExcessObject*> open;
  for (ExcessObject& e : out.objects) {
    if (e.cause == ExcessCause::SeenFiner) continue;
    const auto at = std::lower_bound(pairs.begin(), pairs.end(), std::pair{e.object, e.cell});
    if (seen_in_cell[static_cast<std::size_t>(at - pairs.begin())])
      e.cause = ExcessCause::ElsewhereInCell;
    else
      open.push_back(&e);
  }

  // The cells of the open objects, baked as the file was (which must give its PVS), then with
  // one more mechanism relaxed per pass; an object that a pass leaves out is put down to it.
  auto open_cells = [&] {
    std::vector<std::uint32_t> cells;
    for (const ExcessObject* e : open) cells.push_back(e->cell);
    std::sort(cells.begin(), cells.end());
    cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
    return cells;
  };
  std::vector<std::uint32_t> cells = open_cells();
  out.cells_rebaked = cells.size();
  if (!cells.empty()) {
    const auto as_filed =
        bake_cells(city, bake, cells, threads, [&](const auto& s) { check_same_cells(s, pvs); });
    runtime::PvsDecoder decoder(pvs);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (decoder.decode(cells[i]) != runtime::Status::kOk ||
          !std::equal(decoder.begin(), decoder.end(), as_filed[i].begin(), as_filed[i].end()))
        throw std::runtime_error("cell " + std::to_string(cells[i]) +
                                 ": the file's PVS is not what its settings bake (another "
                                 "version of urbanpvs-preprocess, or a changed file?)");
    }
  }
  preprocess::BakeOptions relaxed = bake;
  for (const ExcessCause cause :
       {ExcessCause::Epsilon, ExcessCause::FarField, ExcessCause::Pixel}) {
    if (cells.empty()) break;
    // Cumulative, but the finer pixel goes with the bake's own maps: maps grown over a whole
    // city at a quarter of the pixel would be 16x larger (and the far field was shown to lose
    // nothing against them, README "Where the excess comes from").
    if (cause == ExcessCause::Epsilon) relaxed.shrink_override = 0;
    if (cause == ExcessCause::FarField) relaxed.max_map = 65536;
    if (cause == ExcessCause::Pixel) {
      relaxed.pixel = bake.pixel / options.pixel_divisor;
      relaxed.max_map = bake.max_map;
    }
    const auto baked = bake_cells(city, relaxed, cells, threads);
    std::vector<ExcessObject*> still;
    for (ExcessObject* e : open) {
      const auto& list =
          baked[std::lower_bound(cells.begin(), cells.end(), e->cell) - cells.begin()];
      if (std::binary_search(list.begin(), list.end(), e->object))
        still.push_back(e);
      else
        e->cause = cause;
    }
    open = std::move(still);
    cells = open_cells();
  }
  for (const ExcessObject& e : out.objects) ++out.counts[static_cast<std::size_t>(e.cause)];
  return out;
}

}  // namespace urbanpvs::explain
