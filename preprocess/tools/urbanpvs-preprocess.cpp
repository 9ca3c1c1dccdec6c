// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-preprocess CITY... -o OUT.pvs: the batch bake of a whole city (see README, "Tools").
// Under an MPI launcher (mpirun -n N urbanpvs-preprocess ...) every rank runs this same main:
// see DistributedBake.hpp.
#include <cstdio>
#include <memory>
#include <stdexcept>

#include "urbanpvs/preprocess/bake/MpiJob.hpp"
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"

int main(int argc, char** argv) {
  using namespace urbanpvs::preprocess;
  std::unique_ptr<MpiJob> job;
  try {
    job = std::make_unique<MpiJob>(&argc, &argv);
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "urbanpvs-preprocess: %s\n", e.what());
    return kExitUsage;
  }
  PreprocessRequest request;
  if (const auto stop = parse_preprocess_command_line(argc, argv, request)) return *stop;
  return run_preprocess(request, *job);
}
