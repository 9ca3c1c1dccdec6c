// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/city/ReadSettings.hpp"

#include <nlohmann/json.hpp>

namespace urbanpvs::geometry {
namespace {

SettingTable<ReadOptions> make_table() {
  using S = SettingStage;
  using R = ReadOptions;
  SettingTable<R> t;
  // The default height is optional: "none" (the default) leaves buildings without a height as
  // objects that occlude nothing.
  auto height = number_setting<R>(
      "default-height", "m", S::Read, 0.01, 1e5,
      "Height of GeoJSON buildings without height attributes; without it they are objects that "
      "occlude nothing, tested up to --max-height",
      {});
  height.default_text = "none";
  height.get = [](const R& r) {
    return r.default_height ? exact(*r.default_height) : std::string("none");
  };
  height.set = [s = height](R& r, const std::string& text) {
    if (text == "none") {
      r.default_height.reset();
      return;
    }
    const double v = setting_detail::parse_number(s.key, text);
    setting_detail::check_limits(s, v, text);
    r.default_height = v;
  };
  t.push_back(std::move(height));
  t.push_back(number_setting<R>("level-height", "m", S::Read, 0.5, 100,
                                "Height of one storey, for building:levels",
                                [](R& r) -> double& { return r.level_height; }));
  t.push_back(choice_setting<R::Coordinates, R>(
      "coordinates", S::Read, {"auto", "geographic", "projected"},
      "GeoJSON coordinates: lon/lat, projected metres, or decided from the values",
      [](R& r) -> R::Coordinates& { return r.coordinates; }));
  t.push_back(flag_setting<R>("strict", S::Read,
                              "Refuse geometry that needs repair (exit 14) instead of repairing "
                              "it or keeping the building as an object that occludes nothing",
                              [](R& r) -> bool& { return r.strict; }));
  t.push_back(number_setting<R>("max-height", "m", S::Read, 1, 1e5,
                                "Tallest plausible building: taller input is refused; buildings "
                                "of unknown height are tested up to it",
                                [](R& r) -> double& { return r.max_height; }));
  // Off by default: the stepped field makes LoD2 bakes tighter but slower (README, "Roofs as
  // stepped height fields"), a trade the user chooses.
  auto roof = number_setting<R>(
      "roof-step", "m", S::Read, 0, 100,
      "CityJSON: occluders as a stepped height field under each roof, with levels at least this "
      "far apart (also on sloped roofs); 0: a level at each roof surface's lowest point; off: "
      "one prism per part at its roof's lowest point",
      {});
  roof.default_text = "off";
  roof.get = [](const R& r) { return r.roof_step ? exact(*r.roof_step) : std::string("off"); };
  roof.set = [s = roof](R& r, const std::string& text) {
    if (text == "off") {
      r.roof_step.reset();
      return;
    }
    const double v = setting_detail::parse_number(s.key, text);
    setting_detail::check_limits(s, v, text);
    r.roof_step = v;
  };
  t.push_back(std::move(roof));
  // On by default since 2026-12-05 (ReadOptions::sloped_roofs says why): --no-sloped-roofs.
  t.push_back(flag_setting<R>("sloped-roofs", S::Read,
                              "CityJSON and CityGML: each roof face rising above its part's "
                              "occluder adds an occluder under its own plane, whose sloped edges "
                              "cast shadows; GeoJSON and OSM: so do the faces of a gabled, "
                              "hipped, pyramidal or skillion roof:shape",
                              [](R& r) -> bool& { return r.sloped_roofs; }));
  auto payload = text_setting<R>("payload", S::Read,
                                 "Attribute (CityJSON), generic attribute (CityGML), property "
                                 "(GeoJSON) or tag (OSM) whose value each object carries "
                                 "into the PVS file, e.g. a mesh or tile key",
                                 [](R& r) -> std::string& { return r.payload_key; });
  // The name is stored in the file, which holds only UTF-8: refuse it here, not after a bake.
  payload.set = [set = payload.set, key = payload.key](R& r, const std::string& text) {
    try {
      (void)nlohmann::json(text).dump();
    } catch (const nlohmann::json::type_error&) {
      setting_detail::refuse(key, "expects a name in UTF-8", text);
    }
    set(r, text);
  };
  t.push_back(std::move(payload));
  t.push_back(text_setting<R>("height-field", S::Read,
                              "GeoJSON property, GIS field or OSM tag holding each building's "
                              "height (e.g. HOEHE), tried before height, building:height and "
                              "measuredHeight",
                              [](R& r) -> std::string& { return r.height_field; }));
  t.push_back(text_setting<R>("layer", S::Read,
                              "Layer of a GeoPackage (or other GIS file) to read; needed when it "
                              "has several layers of polygons",
                              [](R& r) -> std::string& { return r.layer; }));
  auto terrain = path_setting<R>(
      "terrain", S::Read,
      "DEM raster (GeoTIFF, SRTM .hgt; read with GDAL) that GeoJSON/OSM buildings stand on and "
      "view cells follow",
      [](R& r) -> std::string& { return r.terrain_path; });
  terrain.existing_file = true;
  t.push_back(std::move(terrain));
  return t;
}

}  // namespace

const SettingTable<ReadOptions>& read_settings() {
  static const SettingTable<ReadOptions> table = make_table();
  return table;
}

}  // namespace urbanpvs::geometry
