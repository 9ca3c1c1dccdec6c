// SPDX-License-Identifier: MIT
// urbanpvs-inspect: each command on the golden file, the JSON shape, queries, the SVG map, and
// the exit code of every kind of failure (data-driven: arguments → expected code and output).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "FileSurgery.hpp"
#include "GoldenBake.hpp"
#include "Inspect.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

#ifdef URBANPVS_HAVE_NLOHMANN_JSON
#include <nlohmann/json.hpp>
#endif

namespace {

namespace fs = std::filesystem;
namespace rt = urbanpvs::runtime;
using urbanpvs::inspect::run;

const std::string kGolden = std::string(URBANPVS_RUNTIME_GOLDEN_DIR) + "/v1_0.pvs";
const fs::path kTmp = fs::path(URBANPVS_TEST_TMP) / "inspect";

struct Result {
  int code;
  std::string out, err;
};

Result inspect(std::vector<std::string> args, const std::string& stdin_text = "") {
  std::istringstream in(stdin_text);
  std::ostringstream out, err;
  const int code = run(args, in, out, err);
  return {code, out.str(), err.str()};
}

std::string write_tmp(const std::string& name, const std::vector<std::byte>& bytes) {
  fs::create_directories(kTmp);
  const std::string path = (kTmp / name).string();
  rt::write_file_atomic(path, bytes);
  return path;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(Inspect, Summary) {
  const Result r = inspect({kGolden});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* part :
       {"format:      1.0", "CRS \"EPSG:7415\", projected input", "objects:     120",
        "cells:       6", "pvs size:    min 0, mean 35.5, max 96", "culled:      70.42 %",
        "1 bitsets, 2 diffs", "input hash 0123456789abcdef",
        "property:    city = Delft \"centrum\"", "pvs", "ratio"}) {
    EXPECT_TRUE(contains(r.out, part)) << part << "\n" << r.out;
  }
}

TEST(Inspect, Cell) {
  const Result r = inspect({kGolden, "--cell", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "cell 2")) << r.out;
  EXPECT_TRUE(contains(r.out, "(85010.000, 446000.000)")) << r.out;  // input CRS
  EXPECT_TRUE(contains(r.out, "neighbours: none 3 1")) << r.out;
  EXPECT_TRUE(contains(r.out, "diff against cell 1")) << r.out;
  EXPECT_TRUE(contains(r.out, "pvs: 10 of 120 objects")) << r.out;
  EXPECT_TRUE(contains(r.out, "3\tNL.IMBAG.Pand.1003")) << r.out;
  EXPECT_FALSE(contains(r.out, "NL.IMBAG.Pand.1119")) << r.out;
}

TEST(Inspect, Payloads) {
  // v2_1.pvs: the golden bake with a "tile" value for every object but each third (39 of 120:
  // object 23 has one anyway).
  const std::string v21 = std::string(URBANPVS_RUNTIME_GOLDEN_DIR) + "/v2_1.pvs";
  Result r = inspect({v21});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "format:      2.1")) << r.out;
  EXPECT_TRUE(contains(r.out, "payloads:    81 of 120 objects, from \"tile\"\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "payloads           1558 bytes")) << r.out;
  r = inspect({v21, "--cell", "2"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "3\tNL.IMBAG.Pand.1003\ttiles/0/3.glb\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "41\tNL.IMBAG.Pand.1041\n")) << r.out;  // 41 % 3 == 2: none
  r = inspect({v21, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(
      contains(r.out, "{\"index\":23,\"id\":\"NL.IMBAG.Pand.1023\",\"payload\":\"caf\xC3\xA9/23\""))
      << r.out;
  EXPECT_FALSE(contains(inspect({kGolden}).out, "payloads:"));
  EXPECT_FALSE(contains(inspect({kGolden, "--json"}).out, "\"payload\""));
}

TEST(Inspect, JsonDump) {
  const Result r = inspect({kGolden, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
#ifdef URBANPVS_HAVE_NLOHMANN_JSON
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["objects"].size(), 120u);
  EXPECT_EQ(j["objects"][0]["index"], 0);
  EXPECT_EQ(j["objects"][0]["id"], "NL.IMBAG.Pand.1000");
  EXPECT_EQ(j["objects"][0]["bbox"],
            nlohmann::json::array({84996.0, 446012.0, -1.5, 85001.5, 446016.25, 4.5}));
  ASSERT_EQ(j["cells"].size(), 6u);
  EXPECT_EQ(j["cells"][2]["triangle"],
            nlohmann::json::parse("[[85010,446000],[85020,446000],[85010,446010]]"));
  EXPECT_EQ(j["cells"][2]["z"], nlohmann::json::array({0.0, 1.5}));
  EXPECT_EQ(j["cells"][2]["pvs"], nlohmann::json::parse("[0,3,13,27,41,55,69,83,97,111]"));
  EXPECT_EQ(j["cells"][0]["pvs"], nlohmann::json::array());
  EXPECT_EQ(j["cells"][2]["neighbours"], nlohmann::json::parse("[null,3,1]"));
  EXPECT_EQ(j["properties"]["note"], "caf\xC3\xA9\n\ttab");
  EXPECT_EQ(j["properties"]["city"], "Delft \"centrum\"");
  EXPECT_EQ(j["coordinates"], "input");
  EXPECT_EQ(j["settings"]["input_hash"], "0123456789abcdef");
#else
  EXPECT_TRUE(contains(r.out, "\"id\":\"NL.IMBAG.Pand.1000\"")) << r.out;
  EXPECT_TRUE(contains(r.out, "\"pvs\":[0,3,13,27,41,55,69,83,97,111]")) << r.out;
#endif
  EXPECT_TRUE(contains(r.out, "\"note\":\"caf\xC3\xA9\\n\\ttab\"")) << "escaping";
}

TEST(Inspect, QueryFromStdinAndFile) {
  const std::string points =
      "# x y z (input CRS)\n85002 446002 0.25\n\n85012 446002 1.0\n85012,446002,2.5\n0 0 0\n";
  const Result r = inspect({kGolden, "--query"}, points);
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::vector<std::string> l;
  for (std::string line; std::getline(lines, line);) l.push_back(line);
  ASSERT_EQ(l.size(), 4u) << r.out;
  EXPECT_EQ(l[0], "{\"point\":[85002,446002,0.25],\"local\":[2,2,1.75],\"cell\":0,\"pvs\":[]}");
  EXPECT_TRUE(contains(l[1], "\"cell\":2,\"pvs\":[\"NL.IMBAG.Pand.1000\",")) << l[1];
  EXPECT_TRUE(contains(l[1], "\"NL.IMBAG.Pand.1003\"")) << l[1];
  EXPECT_TRUE(contains(l[2], "\"cell\":null")) << l[2];  // above cell 2's prism
  EXPECT_TRUE(contains(l[3], "\"cell\":null,\"pvs\":[]")) << l[3];

  fs::create_directories(kTmp);
  const std::string file = (kTmp / "points.txt").string();
  std::ofstream(file) << "85002 446002 0.25\n";
  const Result from_file = inspect({kGolden, "--query", file});
  ASSERT_EQ(from_file.code, 0) << from_file.err;
  EXPECT_EQ(from_file.out, l[0] + "\n");
}

TEST(Inspect, GeoQuery) {
  rt::PvsBake bake = urbanpvs::test::golden_bake();
  bake.meta.frame = {"EPSG:4326", true, {52.0, 4.0, 0.0}, {0, 0, 0}};
  const std::string path = write_tmp("geo.pvs", rt::encode(bake));
  // lon lat h: 0.0001° east ≈ 6.86 m, 0.00002° north ≈ 2.2 m, inside cell 0.
  const Result r = inspect({path, "--query", "--geo"}, "4.0001 52.00002 1.75\n");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "\"cell\":0")) << r.out;
  EXPECT_EQ(inspect({kGolden, "--query", "--geo"}, "4 52 0\n").code,
            urbanpvs::inspect::kExitBadQuery);
}

TEST(Inspect, Svg) {
  fs::create_directories(kTmp);
  const std::string out = (kTmp / "map.svg").string();
  ASSERT_EQ(inspect({kGolden, "--svg", out, "--cell", "3"}).code, 0);
  std::ifstream in(out);
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_TRUE(contains(svg, "<svg xmlns=\"http://www.w3.org/2000/svg\""));
  EXPECT_TRUE(contains(svg, "id=\"selected-cell\""));
  EXPECT_TRUE(contains(svg, "cell 3 (green) sees 96 objects"));
  EXPECT_TRUE(contains(svg, "</svg>"));
  ASSERT_EQ(inspect({kGolden, "--svg", out}).code, 0);
}

struct Case {
  std::vector<std::string> args;
  int code;
  std::string message;  // part of standard error
};

TEST(Inspect, ExitCodes) {
  using namespace urbanpvs::inspect;
  const auto golden = rt::encode(urbanpvs::test::golden_bake(), urbanpvs::test::golden_options());
  auto bad_magic = golden;
  bad_magic[0] = std::byte{'X'};
  auto newer = golden;
  urbanpvs::test::put_u16(newer, 8, 3);
  auto corrupt = golden;
  corrupt[corrupt.size() - 3] ^= std::byte{1};
  auto truncated = golden;
  truncated.resize(golden.size() / 2);
  const std::vector<Case> cases = {
      {{"--help"}, kExitOk, ""},
      {{}, kExitUsage, "missing FILE"},
      {{kGolden, "--bogus"}, kExitUsage, "unknown option --bogus"},
      {{kGolden, "--cell"}, kExitUsage, "--cell needs a cell index"},
      {{kGolden, "--cell", "x"}, kExitUsage, "--cell needs a cell index"},
      {{kGolden, "--json", "--query"}, kExitUsage, "cannot be combined"},
      {{kGolden, "--geo"}, kExitUsage, "--geo only applies to --query"},
      {{"/nonexistent/x.pvs"}, kExitUnreadable, "/nonexistent/x.pvs: cannot read the file"},
      {{write_tmp("magic.pvs", bad_magic)}, kExitNotPvs, "bad magic"},
      {{write_tmp("newer.pvs", newer)}, kExitUnsupported, "newer major version"},
      {{write_tmp("corrupt.pvs", corrupt)}, kExitCorrupt, "checksum mismatch in section 'pvs'"},
      {{write_tmp("truncated.pvs", truncated)}, kExitCorrupt, "truncated.pvs: file shorter"},
      {{kGolden, "--cell", "6"}, kExitBadQuery, "cell 6 out of range"},
      {{kGolden, "--query", "/nonexistent/points.txt"}, kExitUnreadable, "cannot read the points"},
      {{kGolden, "--svg", "/nonexistent/dir/map.svg"},
       kExitWriteFailed,
       "/nonexistent/dir/map.svg"},
  };
  for (const Case& c : cases) {
    const Result r = inspect(c.args);
    EXPECT_EQ(r.code, c.code) << (c.args.empty() ? "" : c.args.back()) << ": " << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << r.err;
  }
  EXPECT_EQ(inspect({kGolden, "--query"}, "1 2\n").code, kExitBadQuery);
  EXPECT_TRUE(
      contains(inspect({kGolden, "--query"}, "1 2 x\n").err, "line 1: expected three numbers"));
}

TEST(Inspect, RealExecutableExitCodes) {
  // The thin main passes codes through (this runs the installed-style binary, not the library).
  const std::string exe = URBANPVS_INSPECT_EXE;
  EXPECT_EQ(std::system((exe + " " + kGolden + " > /dev/null").c_str()), 0);
  const int status = std::system((exe + " /nonexistent.pvs 2> /dev/null").c_str());
  ASSERT_NE(status, -1);
  EXPECT_EQ(WEXITSTATUS(status), urbanpvs::inspect::kExitUnreadable);
}

}  // namespace
