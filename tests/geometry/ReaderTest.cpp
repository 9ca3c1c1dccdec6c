// SPDX-License-Identifier: GPL-3.0-or-later
// City readers: every malformed file of tests/data/bad raises exactly the InputError listed in
// its EXPECTED.tsv, every file of tests/data/repairable loads with exactly the listed repairs, and
// the real extracts in URBANPVS_SHARED_CITIES (skipped when absent) load as the files say they
// should, checked against the files themselves read independently with nlohmann::json.
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <typeinfo>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#endif

#include "SharedCities.hpp"
#include "TextFile.hpp"
#include "urbanpvs/geometry/city/CityReader.hpp"
#include "urbanpvs/geometry/city/InputError.hpp"
#include "urbanpvs/geometry/city/LocalFrameMapping.hpp"
#include "urbanpvs/geometry/city/RingCleanup.hpp"
#include "urbanpvs/geometry/occluders/PolygonUnion.hpp"

namespace {

namespace fs = std::filesystem;
using namespace urbanpvs::geometry;
// ordered_json keeps the files' order, so "in file order" can be checked.
using Json = nlohmann::ordered_json;

const fs::path kTestData = URBANPVS_TEST_DATA;
using urbanpvs::test::kSharedCities;

using urbanpvs::test::read_text;

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream in(s);
  while (std::getline(in, field, sep)) out.push_back(field);
  if (!s.empty() && s.back() == sep) out.emplace_back();
  return out;
}

// Rows of an EXPECTED.tsv: comment lines (#) and the header (first field "file") are skipped.
std::vector<std::vector<std::string>> tsv_rows(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#' || line.rfind("file\t", 0) == 0) continue;
    rows.push_back(split(line, '\t'));
  }
  return rows;
}

std::optional<InputProblem> problem_named(const std::string& name) {
  static const std::map<std::string, InputProblem> names{
      {"Unreadable", InputProblem::Unreadable},
      {"InvalidJson", InputProblem::InvalidJson},
      {"BadStructure", InputProblem::BadStructure},
      {"UnknownCrs", InputProblem::UnknownCrs},
      {"InvalidGeometry", InputProblem::InvalidGeometry},
      {"MissingHeight", InputProblem::MissingHeight},
      {"EmptyCity", InputProblem::EmptyCity},
      {"UnsupportedFormat", InputProblem::UnsupportedFormat},
      {"Implausible", InputProblem::Implausible},
      {"InvalidXml", InputProblem::InvalidXml}};
  auto it = names.find(name);
  return it == names.end() ? std::nullopt : std::optional<InputProblem>(it->second);
}

// "default_height=12;coordinates=geographic;strict" -> ReadOptions ("-": defaults).
ReadOptions options_from(const std::string& text) {
  ReadOptions o;
  if (text.empty() || text == "-") return o;
  for (const std::string& item : split(text, ';')) {
    const auto eq = item.find('=');
    const std::string key = item.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : item.substr(eq + 1);
    if (key == "default_height") {
      o.default_height = std::stod(value);
    } else if (key == "level_height") {
      o.level_height = std::stod(value);
    } else if (key == "strict") {
      o.strict = true;
    } else if (key == "coordinates") {
      o.coordinates = value == "geographic"  ? ReadOptions::Coordinates::Geographic
                      : value == "projected" ? ReadOptions::Coordinates::Projected
                                             : ReadOptions::Coordinates::Auto;
    } else {
      ADD_FAILURE() << "unknown option \"" << item << "\" in an EXPECTED.tsv";
    }
  }
  return o;
}

std::string test_name(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

// What a read did: loaded a city, raised an InputError, or escaped with anything else.
struct Outcome {
  std::optional<City> city;
  std::optional<InputError> error;
  std::string other;  // description of any other exception
};

Outcome attempt(const std::function<City()>& read) {
  Outcome out;
  try {
    out.city = read();
  } catch (const InputError& e) {
    out.error = e;
  } catch (const std::exception& e) {
    out.other = std::string(typeid(e).name()) + ": " + e.what();
  } catch (...) {
    out.other = "an exception not derived from std::exception";
  }
  return out;
}

// An Outcome reduced to what a test of a bad input checks, so it can cross a process boundary.
struct Summary {
  bool loaded = false;
  std::size_t objects = 0;
  std::optional<InputProblem> problem;
  std::string file, feature, message;
  std::string other;  // another exception, or how the reading process died
};

Summary summarise(const Outcome& o) {
  Summary s;
  s.loaded = o.city.has_value();
  if (o.city) s.objects = o.city->objects.size();
  if (o.error) {
    s.problem = o.error->problem();
    s.file = o.error->file();
    s.feature = o.error->feature();
    s.message = o.error->what();
  }
  s.other = o.other;
  return s;
}

#if defined(__unix__) || defined(__APPLE__)
// Reads in a child process, so that a crash (a reader bug) fails only the test that met it and
// the remaining inputs still run when the executable is started by hand, not just under ctest.
Summary read_isolated(const std::function<City()>& read) {
  std::fflush(nullptr);
  int fds[2];
  if (pipe(fds) != 0) return summarise(attempt(read));
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return summarise(attempt(read));
  }
  if (pid == 0) {
    close(fds[0]);
    const Summary s = summarise(attempt(read));
    std::string wire;
    for (const std::string& field :
         {std::string(s.loaded ? "1" : "0"), std::to_string(s.objects),
          s.problem ? std::to_string(static_cast<int>(*s.problem)) : std::string(), s.file,
          s.feature, s.message, s.other}) {
      wire += field;
      wire += '\0';
    }
    for (std::size_t done = 0; done < wire.size();) {
      const ssize_t n = write(fds[1], wire.data() + done, wire.size() - done);
      if (n <= 0) break;
      done += static_cast<std::size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string wire;
  char buf[4096];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;) wire.append(buf, buf + n);
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  Summary s;
  if (WIFSIGNALED(status)) {
    s.other = "the reader crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
              strsignal(WTERMSIG(status)) + ")";
    return s;
  }
  const std::vector<std::string> f = split(wire, '\0');
  if (f.size() < 7) {
    s.other = "the reading process ended without a result";
    return s;
  }
  s.loaded = f[0] == "1";
  s.objects = std::stoul(f[1]);
  if (!f[2].empty()) s.problem = static_cast<InputProblem>(std::stoi(f[2]));
  s.file = f[3];
  s.feature = f[4];
  s.message = f[5];
  s.other = f[6];
  return s;
}
#else
Summary read_isolated(const std::function<City()>& read) {
  return summarise(attempt(read));
}
#endif

bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

// ---------------------------------------------------------------------------------------------
// Malformed inputs: tests/data/bad/EXPECTED.tsv

struct BadCase {
  std::vector<std::string> files;  // names inside tests/data/bad; the last one is at fault
  std::string problem;             // InputProblem enumerator name
  std::vector<std::string> substrings;
  std::string options;
  std::string feature;  // expected InputError::feature(), "-" unchecked
};

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> cases;
  for (const auto& r : tsv_rows(kTestData / "bad" / "EXPECTED.tsv")) {
    BadCase c;
    c.files = split(r.at(0), '+');
    c.problem = r.size() > 1 ? r[1] : "";
    if (r.size() > 2 && r[2] != "-") c.substrings = split(r[2], '|');
    c.options = r.size() > 3 ? r[3] : "-";
    c.feature = r.size() > 4 ? r[4] : "-";
    cases.push_back(std::move(c));
  }
  return cases;
}

void PrintTo(const BadCase& c, std::ostream* os) {
  for (const std::string& f : c.files) *os << f << ' ';
  *os << "-> " << c.problem;
  if (c.options != "-") *os << " with " << c.options;
}

std::string bad_case_name(const testing::TestParamInfo<BadCase>& info) {
  std::string name;
  for (const std::string& f : info.param.files) name += (name.empty() ? "" : "_and_") + f;
  if (info.param.options != "-") name += "_with_" + info.param.options;
  return test_name(name);
}

class BadInput : public testing::TestWithParam<BadCase> {
 protected:
  // Checks that `out` is exactly the expected InputError for a read of `file_name` whose
  // message must name `file_name`.
  void expect_error(const Summary& out, const std::string& file_name) const {
    const BadCase& c = GetParam();
    const std::optional<InputProblem> want = problem_named(c.problem);
    ASSERT_TRUE(want) << "EXPECTED.tsv names no InputProblem \"" << c.problem << "\"";
    ASSERT_TRUE(out.other.empty()) << "expected InputError(" << c.problem << "), got " << out.other;
    ASSERT_FALSE(out.loaded) << "expected InputError(" << c.problem << "), but the input loaded "
                             << out.objects << " objects";
    ASSERT_TRUE(out.problem);
    const std::string& message = out.message;
    EXPECT_EQ(*out.problem, *want) << "got \"" << to_string(*out.problem) << "\": " << message;
    EXPECT_TRUE(contains(message, file_name)) << "message does not name the file: " << message;
    EXPECT_TRUE(contains(message, to_string(*want))) << message;
    for (const std::string& s : c.substrings)
      EXPECT_TRUE(contains(message, s)) << "message lacks \"" << s << "\": " << message;
    if (c.feature != "-") {
      EXPECT_EQ(out.feature, c.feature) << message;
    }
  }
};

TEST_P(BadInput, ReadCityRaisesTheExpectedProblem) {
  const BadCase& c = GetParam();
  std::vector<std::string> paths;
  for (const std::string& f : c.files) paths.push_back((kTestData / "bad" / f).string());
  const Summary out = read_isolated([&] { return read_city(paths, options_from(c.options)); });
  expect_error(out, c.files.back());
  if (out.problem) {
    EXPECT_EQ(out.file, paths.back());
  }
}

TEST_P(BadInput, ReadCityTextRaisesTheSameProblem) {
  const BadCase& c = GetParam();
  if (c.files.size() != 1) GTEST_SKIP() << "needs several files; read_city_text reads one";
  const std::string text = read_text(kTestData / "bad" / c.files[0]);
  const Summary out =
      read_isolated([&] { return read_city_text(text, c.files[0], options_from(c.options)); });
  expect_error(out, c.files[0]);
  if (out.problem) {
    EXPECT_EQ(out.file, c.files[0]);
  }
}

INSTANTIATE_TEST_SUITE_P(Files, BadInput, testing::ValuesIn(bad_cases()), bad_case_name);

TEST(BadInputData, EveryFileHasAnExpectation) {
  const std::vector<BadCase> cases = bad_cases();
  EXPECT_GE(cases.size(), 24u);
  std::set<std::string> listed;
  for (const BadCase& c : cases) {
    EXPECT_TRUE(problem_named(c.problem)) << c.problem;
    for (const std::string& f : c.files) {
      listed.insert(f);
      EXPECT_TRUE(fs::is_regular_file(kTestData / "bad" / f)) << f << " is listed but absent";
    }
  }
  for (const auto& entry : fs::directory_iterator(kTestData / "bad")) {
    const std::string name = entry.path().filename().string();
    if (name != "EXPECTED.tsv") {
      EXPECT_TRUE(listed.count(name)) << name << " has no expectation";
    }
  }
}

TEST(ReadCity, MissingFileIsUnreadable) {
  const std::string path = (kTestData / "bad" / "no_such_file.city.json").string();
  const Outcome out = attempt([&] { return read_city({path}); });
  ASSERT_TRUE(out.error) << out.other;
  EXPECT_EQ(out.error->problem(), InputProblem::Unreadable);
  EXPECT_EQ(out.error->file(), path);
  EXPECT_TRUE(contains(out.error->what(), path)) << out.error->what();
}

TEST(ReadCity, DirectoryIsUnreadable) {
  // A folder opens like a file on Linux, but reading it fails: that is no empty JSON text.
  const std::string path = (kTestData / "bad").string();
  const Outcome out = attempt([&] { return read_city({path}); });
  ASSERT_TRUE(out.error) << out.other;
  EXPECT_EQ(out.error->problem(), InputProblem::Unreadable) << out.error->what();
  EXPECT_TRUE(contains(out.error->what(), path)) << out.error->what();
}

TEST(ReadCity, NoFileIsAnError) {
  const Outcome out = attempt([] { return read_city({}); });
  ASSERT_TRUE(out.error) << out.other;
  EXPECT_EQ(out.error->problem(), InputProblem::EmptyCity);
}

// GeoJSON as exporters write it beyond Polygon and MultiPolygon: a GeometryCollection holding a
// building's polygon (and a point), a MultiPolygon with an empty member, and features whose
// rings hold no position. The city reads: the collection's polygon is the building, the empty
// member is left out with a warning, a feature without any position is skipped with one;
// --strict still refuses the empty member.
TEST(ReadCity, GeoJsonCollectionsAndEmptyPolygonsAreReadNotRefused) {
  const std::string square =
      "[[85000,446000],[85010,446000],[85010,446010],[85000,446010],"
      "[85000,446000]]";
  const std::string other =
      "[[85020,446000],[85030,446000],[85030,446010],[85020,446010],"
      "[85020,446000]]";
  auto feature = [](const std::string& id, const std::string& geometry) {
    return R"({"type":"Feature","id":")" + id + R"(","properties":{"height":10},"geometry":)" +
           geometry + "}";
  };
  const std::string text =
      R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"EPSG:28992"}},)"
      R"("features":[)" +
      feature("collection", R"({"type":"GeometryCollection","geometries":[{"type":"Polygon",)"
                            R"("coordinates":[)" +
                                square + R"(]},{"type":"Point","coordinates":[85005,446005]}]})") +
      "," +
      feature("empty-member", R"({"type":"MultiPolygon","coordinates":[[],[)" + other + "]]}") +
      "," + feature("empty-ring", R"({"type":"Polygon","coordinates":[[]]})") + "," +
      feature("no-rings", R"({"type":"Polygon","coordinates":[]})") + "]}";
  const City city = read_city_text(text, "exported.geojson", {});
  ASSERT_EQ(city.objects.size(), 2u);
  EXPECT_EQ(city.objects[0].source_id, "collection");
  EXPECT_NEAR(area(city.objects[0].footprint.at(0)), 100, 1e-6);
  EXPECT_EQ(city.objects[1].source_id, "empty-member");
  EXPECT_NEAR(area(city.objects[1].footprint.at(0)), 100, 1e-6);
  auto warned = [&](const std::string& what) {
    return std::any_of(city.report.warnings.begin(), city.report.warnings.end(),
                       [&](const std::string& w) { return w.find(what) != std::string::npos; });
  };
  EXPECT_TRUE(warned("exported.geojson: empty-member: 1 polygon(s) without rings left out"));
  EXPECT_TRUE(warned("exported.geojson: empty-ring: no coordinates: skipped"));
  EXPECT_TRUE(
      warned("no-rings: invalid geometry: polygon without rings (no coordinates: skipped)"));
  ReadOptions strict;
  strict.strict = true;
  try {
    read_city_text(text, "exported.geojson", strict);
    ADD_FAILURE() << "--strict read an empty polygon";
  } catch (const InputError& e) {
    EXPECT_EQ(e.problem(), InputProblem::InvalidGeometry);
    EXPECT_EQ(e.feature(), "empty-member");
  }
}

// A CityJSON surface without rings (`[]` in a shell) has no area: the building reads as it
// does without it, and the city is not refused.
TEST(ReadCity, CityJsonEmptySurfaceIsPassedOver) {
  auto city_with = [](const std::string& extra) {
    const std::string shell =
        "[[[0,3,2,1]],[[4,5,6,7]],[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]]," + extra + "[[3,0,4,7]]]";
    const std::string text =
        R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,0.001],)"
        R"("translate":[85000,446000,0]},"metadata":{"referenceSystem":)"
        R"("https://www.opengis.net/def/crs/EPSG/0/7415"},"CityObjects":{"b":{"type":"Building",)"
        R"("geometry":[{"type":"Solid","lod":"2","boundaries":[)" +
        shell +
        R"(]}]}},"vertices":[[0,0,0],[10000,0,0],[10000,10000,0],[0,10000,0],[0,0,10000],)"
        R"([10000,0,10000],[10000,10000,10000],[0,10000,10000]]})";
    return read_city_text(text, "shell.city.json", {});
  };
  const City plain = city_with("");
  const City with_empty = city_with("[],");
  ASSERT_EQ(with_empty.objects.size(), 1u);
  ASSERT_EQ(plain.objects.size(), 1u);
  const CityObject& a = plain.objects[0];
  const CityObject& b = with_empty.objects[0];
  ASSERT_EQ(b.occluders.size(), a.occluders.size());
  ASSERT_EQ(b.occluders.size(), 1u);
  EXPECT_EQ(b.occluders[0].top_z, 10);
  EXPECT_NEAR(area(b.occluders[0].footprint), 100, 1e-6);
  EXPECT_EQ(b.surfaces.size(), a.surfaces.size());
}

// Only a Building or BuildingPart that lists a BuildingPart among its children reads it (with
// itself); an object whose "parents" name anything else (a CityObjectGroup, as CityJSON 2.0
// group members may; an extension's type; a building that does not list it) is read on its
// own. The reader once skipped every object with any known parent: a group member vanished
// without a word (the CityJSON conformance corpus's cityjson_fake_complete).
TEST(ReadCity, CityJsonObjectsUnderParentsThatReadNothingOfThemAreKept) {
  // Boxes of 10 x 10 m, 12 m high, 20 m apart along x: box k uses vertices 8k .. 8k + 7.
  auto box = [](int k) {
    std::string b = "[";
    const int v = 8 * k;
    const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                             {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
    for (int f = 0; f < 6; ++f) {
      b += f ? ",[[" : "[[";
      for (int i = 0; i < 4; ++i) b += (i ? "," : "") + std::to_string(v + faces[f][i]);
      b += "]]";
    }
    return b + "]";
  };
  std::string vertices;
  for (int k = 0; k < 5; ++k)
    for (const auto& [x, y, z] : std::vector<std::array<int, 3>>{{0, 0, 0},
                                                                 {10, 0, 0},
                                                                 {10, 10, 0},
                                                                 {0, 10, 0},
                                                                 {0, 0, 12},
                                                                 {10, 0, 12},
                                                                 {10, 10, 12},
                                                                 {0, 10, 12}})
      vertices += std::string(vertices.empty() ? "" : ",") + "[" + std::to_string(x + 20 * k) +
                  "," + std::to_string(y) + "," + std::to_string(z) + "]";
  auto solid = [&](int k) {
    return R"("geometry":[{"type":"MultiSurface","lod":"1","boundaries":)" + box(k) + "}]";
  };
  const std::string text =
      R"({"type":"CityJSON","version":"2.0","transform":{"scale":[1,1,1],)"
      R"("translate":[85000,446000,0]},"metadata":{"referenceSystem":)"
      R"("https://www.opengis.net/def/crs/EPSG/0/7415"},"CityObjects":{)"
      R"("grp":{"type":"CityObjectGroup","children_roles":[],"children":["member"]},)"
      R"("member":{"type":"Building","parents":["grp"],)" +
      solid(0) + "}," +
      R"("noise":{"type":"+NoiseBuilding","children":["part_of_noise"]},)"
      R"("part_of_noise":{"type":"BuildingPart","parents":["noise"],)" +
      solid(1) + "}," +
      R"("house":{"type":"Building","children":["wing"]},)"
      R"("wing":{"type":"BuildingPart","parents":["house"],)" +
      solid(2) + "}," + R"("stray":{"type":"BuildingPart","parents":["house"],)" + solid(3) + "}," +
      R"("annex":{"type":"Building","parents":["house"],)" + solid(4) +
      "}},"
      R"("vertices":[)" +
      vertices + "]}";
  const City city = read_city_text(text, "parents.city.json", {});
  std::vector<std::string> ids;
  for (const CityObject& o : city.objects) ids.push_back(o.source_id);
  // "wing" is read with "house"; every other building or part is an object of its own.
  EXPECT_EQ(ids, (std::vector<std::string>{"member", "part_of_noise", "house", "stray", "annex"}));
  for (const CityObject& o : city.objects) {
    EXPECT_TRUE(o.occludes) << o.source_id;
    EXPECT_NEAR(o.bbox.zmax - o.bbox.zmin, 12.0, 1e-9) << o.source_id;
  }
  // The house holds its wing: the box 40 .. 50 m east of the first.
  const CityObject& house = city.objects[2];
  EXPECT_NEAR(house.bbox.xy.max.x - city.objects[0].bbox.xy.min.x, 50.0, 1e-9);
}

// A GroundSurface holds a prism up only when walls stand round it. A shell that misses walls
// (an XLink to a wall that is not in the file) let the validator's rays through where the prism
// blocked them (misses on go-citygml's citygml10_building_parts.gml). A roof that closes over a
// hole in the ground, with walls only round the outside, keeps its occluder, hole and all.
TEST(ReadCity, CityJsonGroundSurfacesHoldOccludersOnlyOnWalls) {
  // A 10 x 10 m part, 8 m high; ground vertices 0-3, roof 4-7, a 4 x 4 m hole in the ground
  // at 8-11 (when `hole`).
  auto city = [](const std::string& walls, bool hole) {
    const std::string ground = hole ? "[[0,3,2,1],[8,9,10,11]]" : "[[0,3,2,1]]";
    const std::string text =
        R"({"type":"CityJSON","version":"2.0","transform":{"scale":[0.001,0.001,0.001],)"
        R"("translate":[85000,446000,0]},"metadata":{"referenceSystem":)"
        R"("https://www.opengis.net/def/crs/EPSG/0/7415"},"CityObjects":{"b":{)"
        R"("type":"Building","geometry":[{"type":"MultiSurface","lod":"2","boundaries":[)" +
        ground + ",[[4,5,6,7]]" + walls +
        R"(],"semantics":{"surfaces":[{"type":"GroundSurface"},{"type":"RoofSurface"},)"
        R"({"type":"WallSurface"}],"values":[0,1)" +
        std::string(walls.empty()                ? ""
                    : walls == R"(,[[0,1,5,4]])" ? ",2"
                                                 : ",2,2,2,2") +
        R"(]}}]}},"vertices":[[0,0,0],[10000,0,0],[10000,10000,0],[0,10000,0],)"
        R"([0,0,8000],[10000,0,8000],[10000,10000,8000],[0,10000,8000],)"
        R"([3000,3000,0],[3000,7000,0],[7000,7000,0],[7000,3000,0]]})";
    return read_city_text(text, "walls.city.json", {});
  };
  const std::string all_walls = R"(,[[0,1,5,4]],[[1,2,6,5]],[[2,3,7,6]],[[3,0,4,7]])";
  const City closed = city(all_walls, false);
  ASSERT_EQ(closed.objects.size(), 1u);
  EXPECT_TRUE(closed.objects[0].occludes);
  ASSERT_EQ(closed.objects[0].occluders.size(), 1u);
  EXPECT_NEAR(area(closed.objects[0].occluders[0].footprint), 100, 1e-6);
  EXPECT_EQ(closed.report.grounds_off_walls, 0u);

  for (const std::string& walls : {std::string(), std::string(R"(,[[0,1,5,4]])")}) {
    const City open = city(walls, false);
    ASSERT_EQ(open.objects.size(), 1u);
    EXPECT_FALSE(open.objects[0].occludes) << walls;
    EXPECT_TRUE(open.objects[0].occluders.empty()) << walls;
    EXPECT_EQ(open.report.grounds_off_walls, 1u) << walls;
    EXPECT_NEAR(open.objects[0].bbox.zmax - open.objects[0].bbox.zmin, 8, 1e-9);
  }

  const City courtyard = city(all_walls, true);
  ASSERT_EQ(courtyard.objects.size(), 1u);
  EXPECT_TRUE(courtyard.objects[0].occludes);
  EXPECT_EQ(courtyard.report.grounds_off_walls, 0u);
  double sum = 0;
  for (const auto& o : courtyard.objects[0].occluders) {
    sum += area(o.footprint);
    EXPECT_EQ(o.footprint.holes.size(), 1u);
  }
  EXPECT_NEAR(sum, 100 - 16, 1e-6);
}

TEST(ReadCity, FilesInOneCrsAreReadTogether) {
  // The counterpart of mixed_crs_a + mixed_crs_b: the same file twice shares its CRS.
  const std::string a = (kTestData / "bad" / "mixed_crs_a.city.json").string();
  const Outcome out = attempt([&] { return read_city({a, a}); });
  ASSERT_TRUE(out.city) << (out.error ? out.error->what() : out.other);
  EXPECT_EQ(out.city->objects.size(), 2u);
  EXPECT_EQ(out.city->sources, (std::vector<std::string>{a, a}));
  EXPECT_EQ(out.city->frame.crs, "EPSG:7415");
}

// ---------------------------------------------------------------------------------------------
// Repairable inputs: tests/data/repairable/EXPECTED.tsv

struct RepairCase {
  std::string file;
  std::size_t objects = 0, duplicate_points = 0, orientation = 0, unclosed = 0;
  std::string options;
};

void PrintTo(const RepairCase& c, std::ostream* os) {
  *os << c.file;
}

std::vector<RepairCase> repair_cases() {
  std::vector<RepairCase> cases;
  for (const auto& r : tsv_rows(kTestData / "repairable" / "EXPECTED.tsv")) {
    if (r.size() < 5) continue;
    cases.push_back({r[0], std::stoul(r[1]), std::stoul(r[2]), std::stoul(r[3]), std::stoul(r[4]),
                     r.size() > 5 ? r[5] : "-"});
  }
  return cases;
}

std::string repair_case_name(const testing::TestParamInfo<RepairCase>& info) {
  return test_name(info.param.file);
}

class RepairableInput : public testing::TestWithParam<RepairCase> {};

TEST_P(RepairableInput, LoadsWithExactlyTheExpectedRepairs) {
  const RepairCase& c = GetParam();
  const std::string path = (kTestData / "repairable" / c.file).string();
  const Outcome out = attempt([&] { return read_city({path}, options_from(c.options)); });
  ASSERT_TRUE(out.city) << (out.error ? out.error->what() : out.other);
  const City& city = *out.city;
  EXPECT_EQ(city.objects.size(), c.objects);
  EXPECT_EQ(city.report.repaired_duplicate_points, c.duplicate_points);
  EXPECT_EQ(city.report.repaired_orientation, c.orientation);
  EXPECT_EQ(city.report.repaired_unclosed, c.unclosed);
  EXPECT_TRUE(city.report.repairs.empty()) << city.report.repairs.front();
  EXPECT_TRUE(city.report.non_occluding.empty()) << city.report.non_occluding.front();
  for (const CityObject& o : city.objects) {
    EXPECT_FALSE(o.occluders.empty()) << o.source_id;
    for (const Polygon& p : o.footprint) {
      EXPECT_EQ(polygon_defect(p), "") << o.source_id;
      EXPECT_GT(signed_area2(p.outer), 0) << o.source_id << ": outer ring not counter-clockwise";
      for (const Ring& h : p.holes)
        EXPECT_LT(signed_area2(h), 0) << o.source_id << ": hole not clockwise";
      for (std::size_t i = 0; i < p.outer.size(); ++i)
        EXPECT_NE(p.outer[i], p.outer[(i + 1) % p.outer.size()])
            << o.source_id << ": repeated point";
    }
  }
  // The same text read from memory repairs the same.
  const Outcome again =
      attempt([&] { return read_city_text(read_text(path), c.file, options_from(c.options)); });
  ASSERT_TRUE(again.city) << (again.error ? again.error->what() : again.other);
  EXPECT_EQ(again.city->report.repaired_duplicate_points, c.duplicate_points);
  EXPECT_EQ(again.city->report.repaired_orientation, c.orientation);
  EXPECT_EQ(again.city->report.repaired_unclosed, c.unclosed);
}

INSTANTIATE_TEST_SUITE_P(Files, RepairableInput, testing::ValuesIn(repair_cases()),
                         repair_case_name);

TEST(RepairableInputData, EveryFileHasAnExpectation) {
  std::set<std::string> listed;
  for (const RepairCase& c : repair_cases()) listed.insert(c.file);
  EXPECT_GE(listed.size(), 4u);
  for (const auto& entry : fs::directory_iterator(kTestData / "repairable")) {
    const std::string name = entry.path().filename().string();
    if (name != "EXPECTED.tsv") {
      EXPECT_TRUE(listed.count(name)) << name << " has no expectation";
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Real cities (URBANPVS_SHARED_CITIES)

Json load_json(const std::string& path) {
  std::ifstream in(path);
  return Json::parse(in);
}

// CityJSON vertex i in input coordinates.
std::array<double, 3> cityjson_vertex(const Json& doc, std::size_t i) {
  const Json& v = doc["vertices"][i];
  std::array<double, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[k] = v[k].get<double>() * doc["transform"]["scale"][k].get<double>() +
             doc["transform"]["translate"][k].get<double>();
  return out;
}

// Calls f(vertex index) for every vertex index below `boundaries` (any nesting).
void for_each_index(const Json& boundaries, const std::function<void(std::size_t)>& f) {
  if (boundaries.is_number()) {
    f(boundaries.get<std::size_t>());
    return;
  }
  for (const Json& b : boundaries) for_each_index(b, f);
}

std::vector<std::string> keys_of_type(const Json& doc, const std::string& type) {
  std::vector<std::string> keys;
  for (auto it = doc["CityObjects"].begin(); it != doc["CityObjects"].end(); ++it)
    if (it.value()["type"] == type) keys.push_back(it.key());
  return keys;
}

std::vector<std::string> source_ids(const City& city) {
  std::vector<std::string> ids;
  for (const CityObject& o : city.objects) ids.push_back(o.source_id);
  return ids;
}

TEST(Delft, ObjectsAreTheBuildingsInFileOrder) {
  REQUIRE_SHARED_CITY(path, "delft.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  const std::vector<std::string> buildings = keys_of_type(doc, "Building");
  ASSERT_EQ(buildings.size(), 160u);
  ASSERT_EQ(city.objects.size(), 160u);
  EXPECT_EQ(source_ids(city), buildings);
  EXPECT_EQ(city.objects.front().source_id, "b1105d28c-00ba-11e6-b420-2bdcc4ab5d7f");
  EXPECT_EQ(city.objects[1].source_id, "b11267a1d-00ba-11e6-b420-2bdcc4ab5d7f");
  EXPECT_EQ(city.objects.back().source_id, "b31e1febd-00ba-11e6-b420-2bdcc4ab5d7f");
  for (std::size_t i = 0; i < city.objects.size(); ++i) EXPECT_EQ(city.objects[i].index, i);
  EXPECT_EQ(city.sources, std::vector<std::string>{path});

  // Every other city object type is counted as ignored, none silently dropped.
  std::map<std::string, std::size_t> others;
  for (const auto& [key, obj] : doc["CityObjects"].items())
    if (obj["type"] != "Building") ++others[obj["type"].get<std::string>()];
  EXPECT_EQ(city.report.ignored_types, others);
}

TEST(Delft, FrameIsTheFilesProjectedCrs) {
  REQUIRE_SHARED_CITY(path, "delft.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Projected);
  EXPECT_EQ(city.frame.crs, "EPSG:7415");
  // The origin is the lower-left corner of all vertices, rounded down to whole metres.
  double xmin = INFINITY, ymin = INFINITY;
  for (std::size_t i = 0; i < doc["vertices"].size(); ++i) {
    const auto v = cityjson_vertex(doc, i);
    xmin = std::min(xmin, v[0]);
    ymin = std::min(ymin, v[1]);
  }
  EXPECT_EQ(city.frame.origin[0], std::floor(xmin));
  EXPECT_EQ(city.frame.origin[1], std::floor(ymin));
  EXPECT_EQ(city.frame.origin[2], 0.0);
}

TEST(Delft, ObjectsLieInsideTheGeographicalExtent) {
  REQUIRE_SHARED_CITY(path, "delft.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  const Json& ext = doc["metadata"]["geographicalExtent"];
  const LocalFrameMapping mapping(city.frame);
  constexpr double tol = 1e-6;
  for (const CityObject& o : city.objects) {
    const auto lo = mapping.to_input(o.bbox.xy.min.x, o.bbox.xy.min.y, o.bbox.zmin);
    const auto hi = mapping.to_input(o.bbox.xy.max.x, o.bbox.xy.max.y, o.bbox.zmax);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(lo[k], ext[k].get<double>() - tol) << o.source_id << " axis " << k;
      EXPECT_LE(hi[k], ext[k + 3].get<double>() + tol) << o.source_id << " axis " << k;
      EXPECT_LE(lo[k], hi[k]) << o.source_id;
    }
  }
}

TEST(Delft, BboxesMatchTheBuildingsVertices) {
  REQUIRE_SHARED_CITY(path, "delft.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  const LocalFrameMapping mapping(city.frame);
  for (const CityObject& o : city.objects) {
    Box3 want;
    for (const Json& g : doc["CityObjects"][o.source_id]["geometry"])
      for_each_index(g["boundaries"], [&](std::size_t i) {
        const auto v = cityjson_vertex(doc, i);
        const auto l = mapping.to_local(v[0], v[1], v[2]);
        want.extend(Vec2{l[0], l[1]}, l[2]);
      });
    EXPECT_NEAR(o.bbox.xy.min.x, want.xy.min.x, 1e-6) << o.source_id;
    EXPECT_NEAR(o.bbox.xy.min.y, want.xy.min.y, 1e-6) << o.source_id;
    EXPECT_NEAR(o.bbox.xy.max.x, want.xy.max.x, 1e-6) << o.source_id;
    EXPECT_NEAR(o.bbox.xy.max.y, want.xy.max.y, 1e-6) << o.source_id;
    EXPECT_NEAR(o.bbox.zmin, want.zmin, 1e-6) << o.source_id;
    EXPECT_NEAR(o.bbox.zmax, want.zmax, 1e-6) << o.source_id;
    EXPECT_DOUBLE_EQ(o.ground_z, o.bbox.zmin) << o.source_id;
  }
}

TEST(Delft, EveryBuildingHasOccludersWithinItsHeight) {
  REQUIRE_SHARED_CITY(path, "delft.city.json");
  const City city = read_city({path});
  for (const CityObject& o : city.objects) {
    EXPECT_FALSE(o.occluders.empty()) << o.source_id;
    EXPECT_FALSE(o.footprint.empty()) << o.source_id;
    for (const OccluderPrism& p : o.occluders) {
      EXPECT_LE(p.top_z, o.bbox.zmax + 1e-9) << o.source_id;
      EXPECT_GT(p.top_z, p.ground_z) << o.source_id << ": occluder without height";
      EXPECT_GE(p.ground_z, o.ground_z - 1e-9) << o.source_id;
      EXPECT_EQ(polygon_defect(p.footprint), "") << o.source_id;
      EXPECT_GT(area(p.footprint), 0.0) << o.source_id;
      // The footprint lies within the object's bbox.
      const Box2 b = bounds(p.footprint);
      EXPECT_GE(b.min.x, o.bbox.xy.min.x - 1e-9) << o.source_id;
      EXPECT_LE(b.max.x, o.bbox.xy.max.x + 1e-9) << o.source_id;
      EXPECT_GE(b.min.y, o.bbox.xy.min.y - 1e-9) << o.source_id;
      EXPECT_LE(b.max.y, o.bbox.xy.max.y + 1e-9) << o.source_id;
    }
  }
}

// Zürich: LoD2 BuildingParts with semantic surfaces.
struct PartFacts {
  std::string id;
  double zmin = INFINITY, zmax = -INFINITY;          // all vertices of the part
  double roof_min = INFINITY, roof_max = -INFINITY;  // outer rings of RoofSurfaces
  bool ground = false;                               // has a GroundSurface
};

// The part's facts from its first geometry (all Zürich parts have exactly one, LoD2).
PartFacts part_facts(const Json& doc, const std::string& id) {
  PartFacts f;
  f.id = id;
  const Json& g = doc["CityObjects"][id]["geometry"][0];
  const Json& surfaces = g["semantics"]["surfaces"];
  const Json& values = g["semantics"]["values"];
  const Json& b = g["boundaries"];
  for (std::size_t s = 0; s < b.size(); ++s) {
    for_each_index(b[s], [&](std::size_t i) {
      const double z = cityjson_vertex(doc, i)[2];
      f.zmin = std::min(f.zmin, z);
      f.zmax = std::max(f.zmax, z);
    });
    if (values[s].is_number() && surfaces[values[s].get<std::size_t>()]["type"] == "GroundSurface")
      f.ground = true;
    if (!values[s].is_number() || surfaces[values[s].get<std::size_t>()]["type"] != "RoofSurface")
      continue;
    for_each_index(b[s][0], [&](std::size_t i) {
      const double z = cityjson_vertex(doc, i)[2];
      f.roof_min = std::min(f.roof_min, z);
      f.roof_max = std::max(f.roof_max, z);
    });
  }
  return f;
}

TEST(Zurich, BuildingPartsMergeIntoTheirBuilding) {
  REQUIRE_SHARED_CITY(path, "zurich_subset_lod2.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  const std::vector<std::string> buildings = keys_of_type(doc, "Building");
  ASSERT_EQ(buildings.size(), 49u);
  ASSERT_EQ(city.objects.size(), 49u);
  EXPECT_EQ(source_ids(city), buildings);
  EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Projected);
  EXPECT_EQ(city.frame.crs, "EPSG:2056");
  EXPECT_TRUE(city.report.ignored_types.empty());
  // 161 parts; the 112 without a GroundSurface are dormers about 10 m above their building's
  // lowest point, without a bottom: raised (thesis 7.1: no occluder over the open space below
  // them; 21 of them reach beyond the ground footprint, over the eaves).
  std::size_t parts = 0, on_ground = 0;
  for (const CityObject& o : city.objects) {
    std::size_t grounded = 0;
    for (const Json& child : doc["CityObjects"][o.source_id]["children"]) {
      const Json& part = doc["CityObjects"][child.get<std::string>()];
      if (part["type"] != "BuildingPart" || !part.contains("geometry") || part["geometry"].empty())
        continue;
      ++parts;
      grounded += part_facts(doc, child.get<std::string>()).ground;
    }
    EXPECT_EQ(o.occluders.size(), grounded) << o.source_id;
    on_ground += grounded;
  }
  EXPECT_EQ(parts, 161u);
  EXPECT_EQ(on_ground, 49u);
  EXPECT_EQ(city.report.raised_parts, 112u);
}

TEST(Zurich, ObjectsLieInsideTheGeographicalExtent) {
  REQUIRE_SHARED_CITY(path, "zurich_subset_lod2.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  const Json& ext = doc["metadata"]["geographicalExtent"];
  const LocalFrameMapping mapping(city.frame);
  for (const CityObject& o : city.objects) {
    const auto lo = mapping.to_input(o.bbox.xy.min.x, o.bbox.xy.min.y, o.bbox.zmin);
    const auto hi = mapping.to_input(o.bbox.xy.max.x, o.bbox.xy.max.y, o.bbox.zmax);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(lo[k], ext[k].get<double>() - 1e-6) << o.source_id << " axis " << k;
      EXPECT_LE(hi[k], ext[k + 3].get<double>() + 1e-6) << o.source_id << " axis " << k;
    }
  }
}

TEST(Zurich, OccludersReachTheEavesNotTheRidge) {
  REQUIRE_SHARED_CITY(path, "zurich_subset_lod2.city.json");
  const City city = read_city({path});
  const Json doc = load_json(path);
  const LocalFrameMapping mapping(city.frame);
  const double z0 = mapping.to_local(0, 0, 0)[2];  // input z -> local z offset
  std::size_t gabled = 0, checked = 0;
  for (const CityObject& o : city.objects) {
    // Parts in the order read_city visits them: the Building's children, in file order.
    std::vector<PartFacts> facts, all;
    for (const Json& child : doc["CityObjects"][o.source_id]["children"]) {
      all.push_back(part_facts(doc, child.get<std::string>()));
      if (all.back().ground) facts.push_back(all.back());  // the others are raised dormers
    }
    ASSERT_EQ(o.occluders.size(), facts.size()) << o.source_id;
    for (std::size_t i = 0; i < facts.size(); ++i) {
      const PartFacts& f = facts[i];
      const OccluderPrism& p = o.occluders[i];
      ASSERT_TRUE(std::isfinite(f.roof_min)) << f.id << " has no RoofSurface";
      EXPECT_NEAR(p.top_z, f.roof_min + z0, 1e-6) << f.id << ": occluder top is not the eaves";
      EXPECT_NEAR(p.ground_z, f.zmin + z0, 1e-6) << f.id;
      EXPECT_LE(p.top_z, o.bbox.zmax) << f.id;
      EXPECT_GT(p.top_z, p.ground_z) << f.id;
      if (f.roof_max - f.roof_min > 0.5) {  // a pitched roof: eaves strictly below the ridge
        ++gabled;
        EXPECT_LT(p.top_z, f.roof_max + z0 - 0.5) << f.id;
        EXPECT_LT(p.top_z, o.bbox.zmax) << f.id;
      }
      ++checked;
    }
    EXPECT_NEAR(o.bbox.zmax,
                std::max_element(
                    all.begin(), all.end(),
                    [](const PartFacts& a, const PartFacts& b) {
                      return a.zmax < b.zmax;
                    })->zmax +
                    z0,
                1e-6)
        << o.source_id;
  }
  EXPECT_EQ(checked, 49u);
  EXPECT_GT(gabled, 20u) << "the extract has many pitched roofs";
}

// Helsinki: OSM GeoJSON in WGS84 lon/lat; most buildings need a default height.
bool is_part(const Json& feature) {
  const Json& p = feature["properties"];
  return p.contains("building:part") && p["building:part"] != "no";
}

std::string osm_id(const Json& feature) {
  const Json& p = feature["properties"];
  return p["@type"].get<std::string>() + "/" + std::to_string(p["@id"].get<long long>());
}

// The outer rings of a feature's polygons in the local frame, counter-clockwise.
std::vector<Polygon> local_outlines(const Json& feature, const LocalFrameMapping& mapping) {
  std::vector<Polygon> out;
  const Json& g = feature["geometry"];
  const auto add = [&](const Json& rings) {
    Polygon p;
    for (const Json& pos : rings[0]) {
      const auto l = mapping.to_local(pos[0].get<double>(), pos[1].get<double>(), 0);
      p.outer.push_back({l[0], l[1]});
    }
    if (p.outer.size() > 1 && p.outer.front() == p.outer.back()) p.outer.pop_back();
    if (signed_area2(p.outer) < 0) std::reverse(p.outer.begin(), p.outer.end());
    out.push_back(std::move(p));
  };
  if (g["type"] == "Polygon") {
    add(g["coordinates"]);
  } else {
    for (const Json& poly : g["coordinates"]) add(poly);
  }
  return out;
}

double total_area(const std::vector<Polygon>& polys) {
  double a = 0;
  for (const Polygon& p : polys) a += area(p);
  return a;
}

TEST(Helsinki, WithoutHeightIsNonOccludingOrWithStrictMissingHeight) {
  REQUIRE_SHARED_CITY(path, "helsinki_buildings.geojson");
  const Json doc = load_json(path);
  std::set<std::string> without_height;
  for (const Json& f : doc["features"]) {
    const Json& p = f["properties"];
    if (!p.contains("height") && !p.contains("building:height") && !p.contains("measuredHeight") &&
        !p.contains("building:levels"))
      without_height.insert(osm_id(f));
  }
  ASSERT_FALSE(without_height.empty());
  // By default they are objects that occlude nothing, each listed by id.
  const City city = read_city({path});
  std::set<std::string> non_occluding;
  for (const CityObject& o : city.objects)
    if (!o.occludes) non_occluding.insert(o.source_id);
  // Each report line names the feature that lacks a height (a building, or a part of one; an
  // outline without height whose parts have heights occludes through its parts).
  for (const std::string& line : city.report.non_occluding) {
    const auto from = line.find(": ") + 2, to = line.find(": no height");
    ASSERT_NE(to, std::string::npos) << line;
    EXPECT_TRUE(without_height.count(line.substr(from, to - from))) << line;
  }
  EXPECT_GT(non_occluding.size(), without_height.size() / 2);
  EXPECT_EQ(city.report.non_occluding.size(), non_occluding.size());
  for (const CityObject& o : city.objects) {
    if (!o.occludes) {
      EXPECT_EQ(o.bbox.zmax, o.ground_z + ReadOptions{}.max_height) << o.source_id;
    }
  }
  ReadOptions strict;
  strict.strict = true;
  const Outcome out = attempt([&] { return read_city({path}, strict); });
  ASSERT_TRUE(out.error) << out.other;
  EXPECT_EQ(out.error->problem(), InputProblem::MissingHeight) << out.error->what();
  EXPECT_EQ(out.error->file(), path);
  EXPECT_TRUE(without_height.count(out.error->feature())) << out.error->what();
  EXPECT_TRUE(contains(out.error->what(), "helsinki_buildings.geojson"));
  EXPECT_TRUE(contains(out.error->what(), out.error->feature()));
}

TEST(Helsinki, BuildingsAndOrphanPartsBecomeObjects) {
  REQUIRE_SHARED_CITY(path, "helsinki_buildings.geojson");
  ReadOptions options;
  options.default_height = 12;
  const City city = read_city({path}, options);
  const Json doc = load_json(path);
  EXPECT_EQ(city.frame.kind, LocalFrame::Kind::Geographic);
  EXPECT_EQ(city.frame.crs, "OGC:CRS84");
  EXPECT_GT(city.report.default_heights, 0u);
  EXPECT_GT(city.report.level_heights, 0u);
  const LocalFrameMapping mapping(city.frame);

  // Independently of the reader's interior-point test: a part belongs to a building when most of
  // its area lies inside the building's outline (exact union areas).
  std::vector<std::pair<std::string, std::vector<Polygon>>> buildings, parts;
  std::size_t tagged_building = 0;
  for (const Json& f : doc["features"]) {
    if (f["properties"].contains("building")) ++tagged_building;
    (is_part(f) ? parts : buildings).emplace_back(osm_id(f), local_outlines(f, mapping));
  }
  EXPECT_EQ(tagged_building, 446u);
  EXPECT_EQ(parts.size(), 133u);  // 126 building:part + 7 tagged both building and building:part
  std::set<std::string> expected;
  for (const auto& b : buildings) expected.insert(b.first);
  std::size_t orphans = 0;
  for (const auto& [id, outline] : parts) {
    const double part_area = total_area(outline);
    bool attached = false;
    Box2 part_box;
    for (const Polygon& p : outline) part_box.extend(bounds(p));
    for (const auto& [bid, boutline] : buildings) {
      Box2 box;
      for (const Polygon& p : boutline) box.extend(bounds(p));
      if (!box.overlaps(part_box)) continue;
      std::vector<Polygon> both = boutline;
      both.insert(both.end(), outline.begin(), outline.end());
      const double shared = total_area(boutline) + part_area - total_area(union_polygons(both));
      if (shared > 0.5 * part_area) attached = true;
    }
    if (!attached) expected.insert(id), ++orphans;
  }
  EXPECT_GT(orphans, 0u);
  const std::vector<std::string> ids = source_ids(city);
  EXPECT_EQ(std::set<std::string>(ids.begin(), ids.end()), expected);
  EXPECT_EQ(ids.size(), expected.size()) << "an id appears twice";
  EXPECT_EQ(city.objects.size(), buildings.size() + orphans);
  for (const std::string& id : ids)
    EXPECT_TRUE(id.rfind("way/", 0) == 0 || id.rfind("relation/", 0) == 0) << id;
  for (const CityObject& o : city.objects) {
    EXPECT_FALSE(o.footprint.empty()) << o.source_id;
    EXPECT_LE(o.bbox.zmin, o.bbox.zmax) << o.source_id;
    for (const OccluderPrism& p : o.occluders) {
      EXPECT_EQ(p.ground_z, 0.0) << o.source_id;
      EXPECT_GT(p.top_z, 0.0) << o.source_id;
      EXPECT_LE(p.top_z, o.bbox.zmax) << o.source_id;
    }
  }
}

TEST(Helsinki, CoordinatesRoundTripThroughTheLocalFrame) {
  REQUIRE_SHARED_CITY(path, "helsinki_buildings.geojson");
  ReadOptions options;
  options.default_height = 12;
  const City city = read_city({path}, options);
  const Json doc = load_json(path);
  const LocalFrameMapping mapping(city.frame);
  std::size_t n = 0;
  double worst = 0;
  for (const Json& f : doc["features"])
    for (const Json& poly : f["geometry"]["coordinates"])
      for (const Json& ring : poly)
        for (const Json& pos : ring) {
          const double lon = pos[0].get<double>(), lat = pos[1].get<double>();
          const auto l = mapping.to_local(lon, lat, 7.5);
          const auto back = mapping.to_input(l[0], l[1], l[2]);
          worst = std::max({worst, std::abs(back[0] - lon), std::abs(back[1] - lat)});
          EXPECT_NEAR(back[2], 7.5, 1e-9);
          ++n;
        }
  EXPECT_GT(n, 5000u);
  EXPECT_LT(worst, 1e-9) << "degrees";

  // The reader uses the same mapping: way/4253124's footprint holds its first vertex.
  const Json& first = doc["features"][0];
  ASSERT_EQ(osm_id(first), "way/4253124");
  const Json& pos = first["geometry"]["coordinates"][0][0][0];
  const auto l = mapping.to_local(pos[0].get<double>(), pos[1].get<double>(), 0);
  const auto it = std::find_if(city.objects.begin(), city.objects.end(),
                               [](const CityObject& o) { return o.source_id == "way/4253124"; });
  ASSERT_NE(it, city.objects.end());
  double nearest = INFINITY;
  for (const Polygon& p : it->footprint)
    for (Vec2 v : p.outer) nearest = std::min(nearest, std::hypot(v.x - l[0], v.y - l[1]));
  EXPECT_LT(nearest, 1e-6) << "m";
}

TEST(Helsinki, LocalDistancesAreGeodesicDistances) {
  REQUIRE_SHARED_CITY(path, "helsinki_buildings.geojson");
  ReadOptions options;
  options.default_height = 12;
  const City city = read_city({path}, options);
  const LocalFrameMapping mapping(city.frame);
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  std::vector<Vec2> points;  // one footprint vertex per object, local
  for (const CityObject& o : city.objects) points.push_back(o.footprint.front().outer.front());
  std::size_t compared = 0;
  double worst = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::size_t j = (i * 37 + 11) % points.size();
    const Vec2 a = points[i], b = points[j];
    const double planar = std::hypot(a.x - b.x, a.y - b.y);
    if (planar < 20 || planar > 2000) continue;
    const auto ga = mapping.to_input(a.x, a.y, 0);
    const auto gb = mapping.to_input(b.x, b.y, 0);
    double geodesic = 0;
    wgs84.Inverse(ga[1], ga[0], gb[1], gb[0], geodesic);
    worst = std::max(worst, std::abs(planar - geodesic) / geodesic);
    ++compared;
  }
  EXPECT_GT(compared, 300u);
  EXPECT_LT(worst, 1e-4);
}

}  // namespace
