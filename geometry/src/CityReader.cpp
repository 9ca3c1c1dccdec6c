// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/geometry/CityReader.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "CityReaders.hpp"
#include "urbanpvs/geometry/InputError.hpp"

namespace urbanpvs::geometry {
namespace detail {

std::string string_member(const Json& obj, const char* key) {
  if (!obj.is_object()) return {};
  const auto it = obj.find(key);
  return it != obj.end() && it->is_string() ? it->get<std::string>() : std::string();
}

double json_number(const Json& v, const std::string& file, const std::string& feature,
                   const char* what) {
  if (!v.is_number())
    throw InputError(InputProblem::BadStructure, file, feature,
                     std::string(what) + " is not a number");
  const double d = v.get<double>();
  if (!std::isfinite(d))
    throw InputError(InputProblem::InvalidGeometry, file, feature,
                     std::string(what) + " is NaN or infinite");
  return d;
}

std::string normalise_crs(const std::string& name, const std::string& file) {
  auto code_after = [&](const std::string& marker) -> std::string {
    const auto pos = name.find(marker);
    if (pos == std::string::npos) return {};
    std::string rest = name.substr(pos + marker.size());
    // "EPSG/0/7415", "EPSG::7415", "EPSG:6.6:4326", "EPSG:7415": the code is the last field.
    const auto cut = rest.find_last_of("/:");
    std::string code = cut == std::string::npos ? rest : rest.substr(cut + 1);
    if (code.empty() || code.find_first_not_of("0123456789") != std::string::npos) return {};
    return code;
  };
  if (name.find("CRS84") != std::string::npos) return "OGC:CRS84";
  if (std::string code = code_after("EPSG"); !code.empty()) return "EPSG:" + code;
  throw InputError(InputProblem::UnknownCrs, file, "", "cannot interpret \"" + name + "\"");
}

bool is_geographic_crs(const std::string& c) {
  return c == "OGC:CRS84" || c == "EPSG:4326" || c == "EPSG:4979";
}

}  // namespace detail

namespace {

using detail::Json;

enum class Format { CityJson, GeoJson };

Json parse(std::string_view text, const std::string& name) {
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() carries "line L, column C" and the byte offset; keep only the readable part.
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(InputProblem::InvalidJson, name, "",
                     what + " (byte " + std::to_string(e.byte) + ")");
  } catch (const nlohmann::json::exception& e) {
    // e.g. out_of_range.406: a number too large for a double (1e400).
    std::string what = e.what();
    if (auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
    throw InputError(InputProblem::InvalidJson, name, "", what);
  }
}

Format detect(const Json& doc, const std::string& name) {
  if (!doc.is_object() || !doc.contains("type") || !doc["type"].is_string())
    throw InputError(InputProblem::UnsupportedFormat, name, "",
                     "neither CityJSON nor GeoJSON (no top-level \"type\")");
  const std::string type = doc["type"].get<std::string>();
  if (type == "CityJSON") return Format::CityJson;
  if (type == "FeatureCollection" || type == "Feature") return Format::GeoJson;
  throw InputError(InputProblem::UnsupportedFormat, name, "",
                   "top-level type \"" + type + "\" is neither CityJSON nor a GeoJSON feature");
}

struct Reader {
  const ReadOptions& options;
  City city;
  std::unique_ptr<LocalFrameMapping> mapping;

  void add(const Json& doc, const std::string& name) {
    const Format format = detect(doc, name);
    const detail::InputScan scan = format == Format::CityJson
                                       ? detail::scan_cityjson(doc, name)
                                       : detail::scan_geojson(doc, name, options);
    if (!mapping) {
      city.frame = choose_local_frame(scan.kind, scan.crs, scan.bounds);
      city.report.coordinate_note = scan.note;
      mapping = std::make_unique<LocalFrameMapping>(city.frame);
    } else if (scan.kind != city.frame.kind ||
               (!scan.crs.empty() && !city.frame.crs.empty() && scan.crs != city.frame.crs)) {
      throw InputError(InputProblem::UnknownCrs, name, "",
                       "reference system " + (scan.crs.empty() ? "(none)" : scan.crs) +
                           " differs from " + city.sources.front() + "'s " +
                           (city.frame.crs.empty() ? "(none)" : city.frame.crs));
    }
    if (format == Format::CityJson)
      detail::load_cityjson(doc, name, *mapping, options, city);
    else
      detail::load_geojson(doc, name, *mapping, options, city);
    city.sources.push_back(name);
  }

  City finish(const std::string& name) {
    if (city.objects.empty())
      throw InputError(InputProblem::EmptyCity, name, "", "no building found");
    for (std::size_t i = 0; i < city.objects.size(); ++i)
      city.objects[i].index = static_cast<std::uint32_t>(i);
    return std::move(city);
  }
};

std::string slurp(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(InputProblem::Unreadable, path, "",
                     std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputProblem::Unreadable, path, "", "cannot open file");
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(InputProblem::Unreadable, path, "", "read failed");
  return s.str();
}

}  // namespace

City read_city(const std::vector<std::string>& paths, const ReadOptions& options) {
  if (paths.empty()) throw InputError(InputProblem::EmptyCity, "(no file)", "", "no input file");
  Reader reader{options, {}, {}};
  for (const std::string& p : paths) reader.add(parse(slurp(p), p), p);
  return reader.finish(paths.back());
}

City read_city_text(std::string_view text, const std::string& name, const ReadOptions& options) {
  Reader reader{options, {}, {}};
  reader.add(parse(text, name), name);
  return reader.finish(name);
}

}  // namespace urbanpvs::geometry
