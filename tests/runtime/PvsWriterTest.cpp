// SPDX-License-Identifier: MIT
// The writer refuses bakes that break the documented constraints, and writes files atomically.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "GoldenBake.hpp"
#include "RandomBake.hpp"
#include "urbanpvs/runtime/FileIo.hpp"
#include "urbanpvs/runtime/PvsFile.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace {

namespace rt = urbanpvs::runtime;
namespace fs = std::filesystem;

void expect_invalid(const rt::PvsBake& bake, const std::string& fragment) {
  const std::string problem = rt::validate(bake);
  EXPECT_NE(problem.find(fragment), std::string::npos) << problem;
  EXPECT_THROW(rt::encode(bake), rt::PvsWriteError);
}

TEST(Writer, ValidatesTheBake) {
  EXPECT_EQ(rt::validate(urbanpvs::test::golden_bake()), "");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto bake = [] { return urbanpvs::test::golden_bake(); };
  rt::PvsBake b = bake();
  b.cells[1].pvs = {3, 2};
  expect_invalid(b, "cell 1: pvs not strictly increasing at position 1");
  b = bake();
  b.cells[1].pvs = {2, 2};
  expect_invalid(b, "cell 1: pvs not strictly increasing");
  b = bake();
  b.cells[2].pvs.push_back(120);
  expect_invalid(b, "cell 2: pvs entry");
  b = bake();
  b.cells[0].neighbours[1] = 6;
  expect_invalid(b, "cell 0: neighbour index out of range");
  b = bake();
  b.cells[3].z_min = 5;
  expect_invalid(b, "cell 3: z range");
  b = bake();
  b.cells[4].triangle[1].x = nan;
  expect_invalid(b, "cell 4: triangle not finite");
  b = bake();
  b.objects[7].bbox[3] = b.objects[7].bbox[0] - 1;
  expect_invalid(b, "object 7: bbox");
  b = bake();
  b.objects[8].source_id = "bad \xC3";
  expect_invalid(b, "object 8: source id is not valid UTF-8");
  b = bake();
  b.meta.frame.crs = "\xFF";
  expect_invalid(b, "metadata: CRS");
  b = bake();
  b.meta.frame.origin[1] = std::numeric_limits<double>::infinity();
  expect_invalid(b, "metadata: frame origin");
  b = bake();
  b.meta.settings.pixel_size_m = nan;
  expect_invalid(b, "metadata: bake settings");
  b = bake();
  b.meta.properties.emplace_back("k", "\xED\xA0\x80");  // a UTF-16 surrogate
  expect_invalid(b, "metadata: property 2");
  b = bake();
  b.objects[9].payload = "tile";
  expect_invalid(b, "object 9: payload given but no payload key");
  b = urbanpvs::test::golden_bake_with_payloads();
  EXPECT_EQ(rt::validate(b), "");
  b.objects[10].payload = "\xC0\x80";  // overlong NUL
  expect_invalid(b, "object 10: payload is not valid UTF-8");
  b = urbanpvs::test::golden_bake_with_payloads();
  b.payload_key = "\xFF";
  expect_invalid(b, "payload key is not valid UTF-8");
}

// A bake whose lists come from pvs_source (the preprocessor's compact store) encodes to the bytes
// of the same lists given as vectors, in every format and coding, and is validated alike.
TEST(Writer, ListsFromASourceGiveTheBytesOfTheVectors) {
  for (double density : {0.02, 0.3, 0.9}) {
    urbanpvs::test::RandomBakeOptions o;
    o.nx = o.ny = 9;
    o.objects = 300;
    o.density = density;
    const rt::PvsBake vectors = urbanpvs::test::random_mesh_bake(11, o);
    rt::PvsBake sourced = vectors;
    for (rt::CellRecord& c : sourced.cells) c.pvs.clear();
    std::size_t asked = 0;
    sourced.pvs_source = [&](std::uint32_t cell, std::vector<std::uint32_t>& out) {
      ++asked;
      out = vectors.cells[cell].pvs;
    };
    for (const auto& [major, coding] :
         {std::pair{2, rt::PvsCoding::kExpGolomb}, std::pair{2, rt::PvsCoding::kVarint},
          std::pair{1, rt::PvsCoding::kVarint}}) {
      rt::EncodeOptions options;
      options.format_major = static_cast<std::uint16_t>(major);
      options.pvs_coding = coding;
      EXPECT_EQ(rt::encode(sourced, options), rt::encode(vectors, options))
          << "density " << density << ", format " << major;
    }
    EXPECT_GT(asked, 3 * vectors.cells.size()) << "validation, full lists and diff candidates";
  }
  rt::PvsBake b = urbanpvs::test::golden_bake();
  const rt::PvsBake lists = b;
  for (rt::CellRecord& c : b.cells) c.pvs.clear();
  b.pvs_source = [&](std::uint32_t cell, std::vector<std::uint32_t>& out) {
    out = lists.cells[cell].pvs;
    if (cell == 3 && out.size() >= 2) std::swap(out[0], out[1]);
  };
  expect_invalid(b, "cell 3: pvs not strictly increasing at position 1");
  b.cells[2].pvs = {1};
  expect_invalid(b, "cell 2: pvs given although the bake has a pvs_source");
}

TEST(Writer, PayloadsNeedVersion2) {
  rt::EncodeOptions v1;
  v1.format_major = 1;
  try {
    rt::encode(urbanpvs::test::golden_bake_with_payloads(), v1);
    FAIL() << "a 1.0 file cannot hold payloads";
  } catch (const rt::PvsWriteError& e) {
    EXPECT_STREQ(e.what(), "object payloads need format 2.1 (format_major 2)");
  }
}

TEST(Writer, Float32BboxesOutsideTheRangeAreRefused) {
  rt::PvsBake b = urbanpvs::test::golden_bake();
  b.objects[0].bbox[3] = 1e39;
  EXPECT_THROW(rt::encode(b), rt::PvsWriteError);
  rt::EncodeOptions exact;
  exact.bbox_float32 = false;
  EXPECT_NO_THROW(rt::encode(b, exact));
}

TEST(Writer, WritesAtomicallyAndReportsThePath) {
  const fs::path dir = fs::path(URBANPVS_TEST_TMP) / "writer";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "out.pvs").string();
  {
    std::ofstream old(path);
    old << "old content";
  }
  const auto bytes = rt::encode(urbanpvs::test::golden_bake(), urbanpvs::test::golden_options());
  rt::write_file_atomic(path, bytes);
  rt::PvsFile file;
  EXPECT_EQ(rt::PvsFile::open_file(path.c_str(), file), rt::Status::kOk);
  EXPECT_EQ(fs::file_size(path), bytes.size());
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.is_regular_file() ? 1 : 0;
  EXPECT_EQ(entries, 1u) << "a temporary file was left behind";

  const std::string missing = (dir / "no" / "such" / "dir" / "x.pvs").string();
  try {
    rt::write_file_atomic(missing, bytes);
    FAIL() << "expected FileWriteError";
  } catch (const rt::FileWriteError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
}

TEST(Writer, ReadFileReportsMissingFiles) {
  std::vector<std::byte> bytes(3);
  EXPECT_EQ(rt::read_file("/nonexistent/urbanpvs.pvs", bytes), rt::Status::kIoError);
  EXPECT_TRUE(bytes.empty());
  rt::PvsFile file;
  rt::LoadError error;
  EXPECT_EQ(rt::PvsFile::open_file("/nonexistent/urbanpvs.pvs", file, {}, &error),
            rt::Status::kIoError);
  EXPECT_EQ(error.status, rt::Status::kIoError);
}

}  // namespace
