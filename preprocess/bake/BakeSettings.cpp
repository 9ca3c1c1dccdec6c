// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/bake/BakeSettings.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace urbanpvs::preprocess {
namespace {

[[noreturn]] void refuse(const Setting& s, const std::string& what, const std::string& text) {
  throw std::invalid_argument("--" + s.key + " " + what + ", got \"" + text + "\"");
}

double parse_number(const Setting& s, const std::string& text) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) refuse(s, "expects a number", text);
  return v;
}

void check_limits(const Setting& s, double v, const std::string& text) {
  if (!(v >= s.min && v <= s.max)) refuse(s, "must be " + s.limits_text(), text);
}

using Access = std::function<double&(PreprocessRequest&)>;

Setting base(std::string key, std::string unit, SettingStage stage, SettingKind kind,
             std::string help, double min = 0, double max = 0) {
  Setting s;
  s.key = std::move(key);
  s.unit = std::move(unit);
  s.stage = stage;
  s.kind = kind;
  s.help = std::move(help);
  s.min = min;
  s.max = max;
  return s;
}

// Builders, one per kind. `field` names the member that holds the value and its default.
Setting number(std::string key, std::string unit, SettingStage stage, double min, double max,
               std::string help, Access field) {
  Setting s =
      base(std::move(key), std::move(unit), stage, SettingKind::Number, std::move(help), min, max);
  s.get = [field](const PreprocessRequest& r) {
    return exact(field(const_cast<PreprocessRequest&>(r)));
  };
  s.set = [field, s](PreprocessRequest& r, const std::string& text) {
    const double v = parse_number(s, text);
    check_limits(s, v, text);
    field(r) = v;
  };
  return s;
}

template <typename Int>
Setting integer(std::string key, std::string unit, SettingStage stage, double min, double max,
                std::string help, std::function<Int&(PreprocessRequest&)> field) {
  Setting s =
      base(std::move(key), std::move(unit), stage, SettingKind::Integer, std::move(help), min, max);
  s.get = [field](const PreprocessRequest& r) {
    return std::to_string(field(const_cast<PreprocessRequest&>(r)));
  };
  s.set = [field, s](PreprocessRequest& r, const std::string& text) {
    const double v = parse_number(s, text);
    if (v != std::floor(v)) refuse(s, "expects an integer", text);
    check_limits(s, v, text);
    field(r) = static_cast<Int>(v);
  };
  return s;
}

Setting flag(std::string key, SettingStage stage, std::string help,
             std::function<bool&(PreprocessRequest&)> field) {
  Setting s = base(std::move(key), "", stage, SettingKind::Flag, std::move(help));
  s.get = [field](const PreprocessRequest& r) {
    return field(const_cast<PreprocessRequest&>(r)) ? "true" : "false";
  };
  s.set = [field, s](PreprocessRequest& r, const std::string& text) {
    if (text != "true" && text != "false") refuse(s, "expects true or false", text);
    field(r) = text == "true";
  };
  return s;
}

// An enum whose values are 0, 1, ... in the order of `names`.
template <typename Enum>
Setting choice(std::string key, SettingStage stage, std::vector<std::string> names,
               std::string help, std::function<Enum&(PreprocessRequest&)> field) {
  Setting s = base(std::move(key), "", stage, SettingKind::Choice, std::move(help));
  s.choices = std::move(names);
  s.get = [field, names = s.choices](const PreprocessRequest& r) {
    return names.at(static_cast<std::size_t>(field(const_cast<PreprocessRequest&>(r))));
  };
  s.set = [field, s](PreprocessRequest& r, const std::string& text) {
    const auto it = std::find(s.choices.begin(), s.choices.end(), text);
    if (it == s.choices.end()) refuse(s, "must be one of " + s.limits_text(), text);
    field(r) = static_cast<Enum>(it - s.choices.begin());
  };
  return s;
}

Setting path(std::string key, SettingStage stage, std::string help,
             std::function<std::string&(PreprocessRequest&)> field) {
  Setting s = base(std::move(key), "", stage, SettingKind::Path, std::move(help));
  s.default_text = "none";
  s.get = [field](const PreprocessRequest& r) {
    const std::string& v = field(const_cast<PreprocessRequest&>(r));
    return v.empty() ? std::string("none") : v;
  };
  s.set = [field](PreprocessRequest& r, const std::string& text) { field(r) = text; };
  return s;
}

std::vector<Setting> make_table() {
  using S = SettingStage;
  using R = PreprocessRequest;
  std::vector<Setting> t;
  // ---- reading (geometry::ReadOptions) ----
  Setting height = number("default-height", "m", S::Read, 0.01, 1e5,
                          "Height of GeoJSON buildings without height attributes; without it "
                          "they are objects that occlude nothing, tested up to --max-height",
                          {});
  height.default_text = "none";
  height.get = [](const R& r) {
    return r.read.default_height ? exact(*r.read.default_height) : std::string("none");
  };
  height.set = [s = height](R& r, const std::string& text) {
    const double v = parse_number(s, text);
    check_limits(s, v, text);
    r.read.default_height = v;
  };
  t.push_back(std::move(height));
  t.push_back(number("level-height", "m", S::Read, 0.5, 100,
                     "Height of one storey, for building:levels",
                     [](R& r) -> double& { return r.read.level_height; }));
  t.push_back(choice<geometry::ReadOptions::Coordinates>(
      "coordinates", S::Read, {"auto", "geographic", "projected"},
      "GeoJSON coordinates: lon/lat, projected metres, or decided from the values",
      [](R& r) -> geometry::ReadOptions::Coordinates& { return r.read.coordinates; }));
  t.push_back(flag("strict", S::Read,
                   "Refuse geometry that needs repair (exit 14) instead of repairing it or "
                   "keeping the building as an object that occludes nothing",
                   [](R& r) -> bool& { return r.read.strict; }));
  t.push_back(number("max-height", "m", S::Read, 1, 1e5,
                     "Tallest plausible building: taller input is refused; buildings of unknown "
                     "height are tested up to it",
                     [](R& r) -> double& { return r.read.max_height; }));
  // ---- blocks and occluders (geometry::BlockOptions; thesis 7) ----
  t.push_back(number("gap", "m", S::Occluders, 0, 10,
                     "Footprints closer than this fuse into one block, and into one obstacle "
                     "for the view cells",
                     [](R& r) -> double& { return r.bake.blocks.gap_tolerance; }));
  t.push_back(number("height-step", "m", S::Occluders, 0, 100,
                     "Occluder tops are rounded down to a multiple of this (0: exact heights)",
                     [](R& r) -> double& { return r.bake.blocks.height_step; }));
  // ---- view cells (geometry::ViewCellOptions; thesis 5.3) ----
  t.push_back(number("epsilon", "m", S::Cells, 0.01, 1000,
                     "Occluder shrinking and sample spacing epsilon (thesis 7.2)",
                     [](R& r) -> double& { return r.bake.cells.epsilon; }));
  t.push_back(number("max-cell-edge", "m", S::Cells, 0.5, 1e4, "Longest view-cell edge",
                     [](R& r) -> double& { return r.bake.cells.max_cell_edge; }));
  Setting band = base("eye-band", "m", S::Cells, SettingKind::Band,
                      "Eye heights above the ground, MIN:MAX", 0, 1000);
  band.get = [](const R& r) {
    return exact(r.bake.cells.eye_min) + ":" + exact(r.bake.cells.eye_max);
  };
  band.set = [s = band](R& r, const std::string& text) {
    const auto colon = text.find(':');
    if (colon == std::string::npos) refuse(s, "expects MIN:MAX in metres", text);
    const double lo = parse_number(s, text.substr(0, colon));
    const double hi = parse_number(s, text.substr(colon + 1));
    if (!(lo >= s.min && lo <= hi && hi <= s.max))
      refuse(s, "must be 0 <= MIN <= MAX <= 1000", text);
    r.bake.cells.eye_min = lo;
    r.bake.cells.eye_max = hi;
  };
  t.push_back(std::move(band));
  Setting region =
      path("region", S::Cells, "GeoJSON (Multi)Polygons in the city's CRS: where view cells go",
           [](R& r) -> std::string& { return r.region_file; });
  region.default_text = "the buildings' bounding rectangles grown by --margin";
  t.push_back(std::move(region));
  t.push_back(number("margin", "m", S::Cells, 0, 1e5,
                     "Without --region, cells go within this distance of a building's "
                     "bounding rectangle",
                     [](R& r) -> double& { return r.bake.cells.margin; }));
  t.push_back(number("narrow-gap", "m", S::Cells, 0, 1,
                     "Slivers of free space thinner than this along a wall get no cells",
                     [](R& r) -> double& { return r.bake.cells.narrow_gap; }));
  t.push_back(number("snap", "m", S::Cells, 0, 10,
                     "Free space's boundary is cleaned within this (near-duplicate points, "
                     "walls closer than it); cells keep gap/2 + snap from every wall",
                     [](R& r) -> double& { return r.bake.cells.snap; }));
  t.push_back(number("min-cell-edge", "m", S::Cells, 0, 1e4,
                     "Cells and walls shorter than this are not refined for shape",
                     [](R& r) -> double& { return r.bake.cells.min_cell_edge; }));
  // ---- cull maps and the hierarchical test (thesis 4, 5.6) ----
  Setting pixel = number("pixel", "m", S::Visibility, 0.001, 1000,
                         "Cull-map pixel size, at most epsilon/(sqrt(2)/2 + 1/128) (thesis 7.2)",
                         [](R& r) -> double& { return r.bake.pixel; });
  pixel.default_text = "that limit, 1.399 for epsilon 1";
  t.push_back(std::move(pixel));
  t.push_back(choice<Backend>("backend", S::Visibility, {"cpu", "osmesa"},
                              "Cull-map renderer: the CPU reference or OSMesa (OpenGL)",
                              [](R& r) -> Backend& { return r.bake.backend; }));
  t.push_back(choice<Method>("method", S::Visibility, {"hierarchical", "brute-force"},
                             "Visibility test: hierarchical (thesis 5.6) or brute force",
                             [](R& r) -> Method& { return r.bake.method; }));
  t.push_back(integer<int>("initial-map", "pixels", S::Visibility, 8, 65536,
                           "Side of the hierarchical test's first cull map",
                           [](R& r) -> int& { return r.bake.initial_map; }));
  t.push_back(integer<int>("max-map", "pixels", S::Visibility, 8, 65536,
                           "Largest cull map (at least --initial-map); beyond it the samples' "
                           "horizons decide (65536: cull maps alone, grown to cover the city)",
                           [](R& r) -> int& { return r.bake.max_map; }));
  // ---- the run (no effect on the result) ----
  Setting threads = integer<unsigned>("threads", "", S::Run, 1, 1024, "Worker threads",
                                      [](R& r) -> unsigned& { return r.threads; });
  threads.default_text = "all cores";
  t.push_back(std::move(threads));
  t.push_back(path("report", S::Run,
                   "Write a JSON report: settings, input hash, counts, stage times, counters, "
                   "peak memory",
                   [](R& r) -> std::string& { return r.report_file; }));
  t.push_back(flag("quiet", S::Run, "No progress and no summary; errors are still printed",
                   [](R& r) -> bool& { return r.quiet; }));
  return t;
}

}  // namespace

std::string exact(double v) {
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, v);
  return std::string(text, result.ptr);
}

std::string Setting::property_key() const {
  std::string k = key;
  std::replace(k.begin(), k.end(), '-', '_');
  return unit == "m" ? k + "_m" : k;
}

std::string Setting::limits_text() const {
  switch (kind) {
    case SettingKind::Number:
    case SettingKind::Integer:
    case SettingKind::Band:
      return exact(min) + " .. " + exact(max) + (unit.empty() ? "" : " " + unit);
    case SettingKind::Choice: {
      std::string out;
      for (const std::string& c : choices) out += (out.empty() ? "" : " | ") + c;
      return out;
    }
    case SettingKind::Flag:
    case SettingKind::Path:
      break;
  }
  return "";
}

const std::vector<Setting>& bake_settings() {
  static const std::vector<Setting> table = make_table();
  return table;
}

const Setting* find_setting(std::string key) {
  std::replace(key.begin(), key.end(), '_', '-');
  for (const Setting& s : bake_settings())
    if (s.key == key) return &s;
  return nullptr;
}

std::vector<std::pair<std::string, std::string>> bake_properties(const BakeOptions& options) {
  PreprocessRequest r;
  r.bake = options;
  std::vector<std::pair<std::string, std::string>> out;
  for (const Setting& s : bake_settings())
    if (s.changes_result() && s.stage != SettingStage::Read && s.kind != SettingKind::Path)
      out.emplace_back(s.property_key(), s.get(r));
  return out;
}

std::vector<std::pair<std::string, std::string>> request_properties(const PreprocessRequest& r) {
  std::vector<std::pair<std::string, std::string>> out = bake_properties(r.bake);
  for (const Setting& s : bake_settings())
    if (s.stage == SettingStage::Read) out.emplace_back(s.property_key(), s.get(r));
  return out;
}

std::string settings_markdown() {
  const PreprocessRequest defaults;
  const char* stage_names[] = {"reading", "occluders", "view cells", "visibility", "run"};
  std::string out =
      "| option | stage | default | limits | stored as | what it does |\n"
      "|---|---|---|---|---|---|\n";
  for (const Setting& s : bake_settings()) {
    std::string value = s.default_text.empty() ? s.get(defaults) : s.default_text;
    if (!s.unit.empty() && s.default_text.empty()) value += " " + s.unit;
    out += "| `--" + s.key + "` | " + stage_names[static_cast<int>(s.stage)] + " | " + value +
           " | " + s.limits_text() + " | " +
           (s.changes_result() ? "`" + s.property_key() + "`" : std::string("-")) + " | " + s.help +
           " |\n";
  }
  return out;
}

}  // namespace urbanpvs::preprocess
