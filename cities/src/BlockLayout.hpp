// Fills one block (a convex lot) with buildings: a perimeter ring around a courtyard, a solid
// row of slices, a tower, or nothing (a park).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "urbanpvs/cities/Model.hpp"
#include "urbanpvs/cities/Params.hpp"

namespace urbanpvs::cities::detail {

struct BlockContent {
  BlockKind kind = BlockKind::Park;
  std::vector<Building> buildings;  ///< ids "<block id>-bNN", block index filled in
};

BlockContent layoutBlock(const Ring& lot, std::uint32_t block_index, const std::string& block_id,
                         const CityParams& params);

}  // namespace urbanpvs::cities::detail
