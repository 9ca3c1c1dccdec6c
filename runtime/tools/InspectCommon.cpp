// SPDX-License-Identifier: MIT
#include "Inspect.hpp"

namespace urbanpvs::inspect {

bool reports_input_coordinates(const runtime::PvsFile& file) {
  return !file.frame().geographic;
}

std::array<double, 3> reported(const runtime::PvsFile& file, double x, double y, double z) {
  // Projected inputs: back to the input CRS, which is what users compare with their data.
  // Geographic inputs: the ENU frame (minus origin) is the only metric frame there is.
  if (reports_input_coordinates(file)) return file.local_to_input(x, y, z);
  return {x, y, z};
}

}  // namespace urbanpvs::inspect
