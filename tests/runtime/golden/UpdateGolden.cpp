// SPDX-License-Identifier: MIT
// Regenerates tests/runtime/golden/v*.pvs and the fuzz seed corpus (target update-golden).
// Run it only when the format changes on purpose: a new version gets a NEW golden file, and the
// old ones stay, decoded forever by GoldenTest.cpp.
//
//   urbanpvs_runtime_update_golden GOLDEN_DIR CORPUS_DIR
#include <cstdio>
#include <string>

#include "GoldenBake.hpp"
#include "RandomBake.hpp"
#include "urbanpvs/runtime/PvsWriter.hpp"

namespace rt = urbanpvs::runtime;

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s GOLDEN_DIR CORPUS_DIR\n", argv[0]);
    return 2;
  }
  const std::string golden = argv[1], corpus = argv[2];
  try {
    const auto golden_bytes =
        rt::encode(urbanpvs::test::golden_bake(), urbanpvs::test::golden_options());
    rt::write_file_atomic(golden + "/v1_0.pvs", golden_bytes);
    const auto golden_v2 =
        rt::encode(urbanpvs::test::golden_bake(), urbanpvs::test::golden_options(2));
    rt::write_file_atomic(golden + "/v2_0.pvs", golden_v2);
    rt::write_file_atomic(corpus + "/golden_v2.pvs", golden_v2);
    const auto golden_v21 =
        rt::encode(urbanpvs::test::golden_bake_with_payloads(), urbanpvs::test::golden_options(2));
    rt::write_file_atomic(golden + "/v2_1.pvs", golden_v21);
    rt::write_file_atomic(corpus + "/golden_v2_1.pvs", golden_v21);
    const auto golden_v22 = rt::encode(urbanpvs::test::golden_bake_with_payloads(),
                                       urbanpvs::test::golden_options(2, 2));
    rt::write_file_atomic(golden + "/v2_2.pvs", golden_v22);
    rt::write_file_atomic(corpus + "/golden_v2_2.pvs", golden_v22);
    // Seeds: small files covering every section feature, so mutations start from valid input.
    rt::write_file_atomic(corpus + "/golden.pvs", golden_bytes);
    rt::write_file_atomic(corpus + "/empty.pvs", rt::encode(rt::PvsBake{}));
    urbanpvs::test::RandomBakeOptions small;
    small.nx = 3;
    small.ny = 2;
    small.objects = 30;
    rt::EncodeOptions chains;
    chains.max_diff_chain = 4;
    chains.diff_threshold = 1.0;
    chains.bbox_float32 = false;
    rt::write_file_atomic(corpus + "/chains.pvs",
                          rt::encode(urbanpvs::test::random_mesh_bake(7, small), chains));
    small.density = 0.9;
    rt::PvsBake geographic = urbanpvs::test::random_mesh_bake(8, small);
    geographic.meta.frame = {"EPSG:4326", true, {52.0116, 4.3571, 0}, {0, 0, 0}};
    rt::write_file_atomic(corpus + "/geographic_dense.pvs", rt::encode(geographic));
    rt::write_file_atomic(corpus + "/soup.pvs",
                          rt::encode(urbanpvs::test::random_soup_bake(9, 12, 50)));
  } catch (const rt::PvsWriteError& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  std::printf("wrote %s/v1_0.pvs, v2_0.pvs, v2_1.pvs, v2_2.pvs and the seeds in %s\n",
              golden.c_str(), corpus.c_str());
  return 0;
}
