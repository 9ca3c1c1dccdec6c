// SPDX-License-Identifier: GPL-3.0-or-later
// urbanpvs-preprocess CITY... -o OUT.pvs: the batch bake of a whole city (see README, "Tools").
#include "urbanpvs/preprocess/bake/PreprocessCommand.hpp"

int main(int argc, char** argv) {
  using namespace urbanpvs::preprocess;
  PreprocessRequest request;
  if (const auto stop = parse_preprocess_command_line(argc, argv, request)) return *stop;
  return run_preprocess(request);
}
