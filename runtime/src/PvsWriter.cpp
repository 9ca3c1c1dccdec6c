// SPDX-License-Identifier: MIT
// encode(): validate the bake, build the point-location grid (1.x), write the sections.
#include "urbanpvs/runtime/PvsWriter.hpp"

#include <cmath>
#include <string>

#include "Container.hpp"
#include "PointLocationGrid.hpp"
#include "Sections.hpp"
#include "Utf8.hpp"
#include "urbanpvs/runtime/Format.hpp"

namespace urbanpvs::runtime {
namespace {

bool valid_string(const std::string& s) {
  return s.size() <= UINT32_MAX &&
         detail::is_valid_utf8(reinterpret_cast<const unsigned char*>(s.data()), s.size());
}

bool all_finite(std::initializer_list<double> values) {
  for (double v : values) {
    if (!std::isfinite(v)) return false;
  }
  return true;
}

std::string validate_metadata(const Metadata& m) {
  const Frame& f = m.frame;
  if (!valid_string(f.crs)) return "metadata: CRS is not valid UTF-8";
  if (!all_finite({f.origin[0], f.origin[1], f.origin[2], f.geodetic_origin.lat_deg,
                   f.geodetic_origin.lon_deg, f.geodetic_origin.h_m}) ||
      std::fabs(f.geodetic_origin.lat_deg) > 90) {
    return "metadata: frame origin not finite (or latitude beyond ±90°)";
  }
  const BakeSettings& s = m.settings;
  if (!all_finite({s.epsilon_m, s.pixel_size_m, s.max_cell_edge_m, s.eye_min_m, s.eye_max_m})) {
    return "metadata: bake settings not finite";
  }
  if (m.properties.size() > UINT32_MAX) return "metadata: too many properties";
  for (std::size_t i = 0; i < m.properties.size(); ++i) {
    if (!valid_string(m.properties[i].first) || !valid_string(m.properties[i].second)) {
      return "metadata: property " + std::to_string(i) + " is not valid UTF-8";
    }
  }
  return {};
}

std::string validate_object(const ObjectRecord& o, std::size_t i) {
  const std::string where = "object " + std::to_string(i) + ": ";
  if (!valid_string(o.source_id)) return where + "source id is not valid UTF-8";
  if (!valid_string(o.payload)) return where + "payload is not valid UTF-8";
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(o.bbox[k]) || !std::isfinite(o.bbox[k + 3]) || o.bbox[k] > o.bbox[k + 3]) {
      return where + "bbox not finite or min > max";
    }
  }
  return {};
}

std::string validate_cell(const CellRecord& c, const std::vector<std::uint32_t>& pvs, std::size_t i,
                          std::size_t cells, std::size_t objects) {
  const std::string where = "cell " + std::to_string(i) + ": ";
  for (const Point2& p : c.triangle) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) return where + "triangle not finite";
  }
  if (!std::isfinite(c.z_min) || !std::isfinite(c.z_max) || c.z_min > c.z_max) {
    return where + "z range not finite or z_min > z_max";
  }
  for (std::uint32_t n : c.neighbours) {
    if (n != kNoCell && n >= cells) return where + "neighbour index out of range";
  }
  for (std::size_t k = 0; k < pvs.size(); ++k) {
    if (pvs[k] >= objects) {
      return where + "pvs entry " + std::to_string(k) + " is not an object index";
    }
    if (k > 0 && pvs[k] <= pvs[k - 1]) {
      return where + "pvs not strictly increasing at position " + std::to_string(k);
    }
  }
  return {};
}

/// The neighbours the diffs are planned over. A coded PVS names a reference by its slot among
/// the neighbours a reader derives from the cells section (they can differ from the bake's, e.g.
/// for cells whose vertices round to the same millimetre), so they are read back from the
/// section just written; otherwise the bake's own.
std::vector<detail::Neighbours> reader_neighbours(const PvsBake& bake,
                                                  const std::vector<detail::SectionBytes>& sections,
                                                  bool coded) {
  if (!coded) {
    std::vector<detail::Neighbours> out;
    out.reserve(bake.cells.size());
    for (const CellRecord& c : bake.cells) out.push_back(c.neighbours);
    return out;
  }
  const std::vector<unsigned char>& cells = sections.back().second;
  detail::CellTable table;
  const char* problem = "";
  if (!detail::read_cells_v2({cells.data(), cells.size(), false}, table, problem)) {
    throw PvsWriteError(std::string("cells: cannot read back what was written: ") + problem);
  }
  return {table.neighbours.begin(), table.neighbours.end()};
}

}  // namespace

std::string validate(const PvsBake& bake) {
  if (bake.objects.size() >= UINT32_MAX) return "too many objects (at most 2^32 - 2)";
  if (bake.cells.size() >= UINT32_MAX) return "too many cells (at most 2^32 - 2)";
  std::string problem = validate_metadata(bake.meta);
  if (problem.empty() && !valid_string(bake.payload_key))
    problem = "payload key is not valid UTF-8";
  for (std::size_t i = 0; problem.empty() && i < bake.objects.size(); ++i) {
    problem = validate_object(bake.objects[i], i);
    if (problem.empty() && bake.payload_key.empty() && !bake.objects[i].payload.empty()) {
      problem = "object " + std::to_string(i) + ": payload given but no payload key";
    }
  }
  const detail::PvsLists lists(bake);
  std::vector<std::uint32_t> buffer;
  for (std::size_t i = 0; problem.empty() && i < bake.cells.size(); ++i) {
    if (bake.pvs_source && !bake.cells[i].pvs.empty())
      return "cell " + std::to_string(i) + ": pvs given although the bake has a pvs_source";
    problem = validate_cell(bake.cells[i], lists.get(static_cast<std::uint32_t>(i), buffer), i,
                            bake.cells.size(), bake.objects.size());
  }
  return problem;
}

std::vector<std::byte> encode(const PvsBake& bake, const EncodeOptions& options) {
  if (const std::string problem = validate(bake); !problem.empty()) throw PvsWriteError(problem);
  if (options.format_major < format::kOldestMajorVersion ||
      options.format_major > format::kMajorVersion) {
    throw PvsWriteError("format_major " + std::to_string(options.format_major) +
                        ": this library writes versions 1 and 2");
  }
  const bool payloads = !bake.payload_key.empty();
  if (payloads && options.format_major < 2) {
    throw PvsWriteError("object payloads need format 2.1 (format_major 2)");
  }
  using format::SectionId;
  std::vector<detail::SectionBytes> sections;
  sections.emplace_back(static_cast<std::uint32_t>(SectionId::kMetadata),
                        detail::write_metadata(bake.meta));
  sections.emplace_back(static_cast<std::uint32_t>(SectionId::kObjects),
                        detail::write_objects(bake.objects, options.bbox_float32));
  if (options.format_major == 1) {
    std::vector<std::array<Point2, 3>> triangles;
    triangles.reserve(bake.cells.size());
    for (const CellRecord& c : bake.cells) triangles.push_back(c.triangle);
    sections.emplace_back(static_cast<std::uint32_t>(SectionId::kCells),
                          detail::write_cells_v1(bake.cells));
    sections.emplace_back(
        static_cast<std::uint32_t>(SectionId::kGrid),
        detail::write_grid(detail::build_grid(triangles, options.grid_cells_per_cell)));
  } else {
    sections.emplace_back(static_cast<std::uint32_t>(SectionId::kCells),
                          detail::write_cells_v2(bake.cells, options));
  }
  const bool coded = options.format_major >= 2 && options.pvs_coding == PvsCoding::kExpGolomb;
  sections.emplace_back(
      static_cast<std::uint32_t>(SectionId::kPvs),
      detail::write_pvs(detail::PvsLists(bake), reader_neighbours(bake, sections, coded), options,
                        coded));
  if (payloads) {
    sections.emplace_back(static_cast<std::uint32_t>(SectionId::kPayloads),
                          detail::write_payloads(bake.payload_key, bake.objects));
  }
  // The lowest minor that holds what the file uses: a coded PVS is 2.2, payloads alone 2.1,
  // neither 2.0 (byte for byte what a 2.0 writer gave).
  const std::uint16_t minor = coded ? 2 : payloads ? 1 : 0;
  return detail::write_container(sections, options.format_major, minor,
                                 coded ? format::kFeatureCodedPvs : 0);
}

}  // namespace urbanpvs::runtime
