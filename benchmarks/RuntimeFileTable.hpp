// SPDX-License-Identifier: MIT
#pragma once

namespace urbanpvs::bench {

/// The table of `runtime_benchmark --files A.pvs ...` (RuntimeFileTable.cpp); argv are the files.
int run_file_table(int argc, char** argv);

}  // namespace urbanpvs::bench
