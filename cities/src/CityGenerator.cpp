// Orchestration: streets first, then each lot becomes a block filled by its own random stream.
#include "urbanpvs/cities/CityGenerator.hpp"

#include <cstdio>
#include <string>

#include "BlockLayout.hpp"
#include "Geometry2d.hpp"
#include "StreetNetwork.hpp"
#include "Terrain.hpp"

namespace urbanpvs::cities {

namespace {

std::string blockId(std::size_t index) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "blk%04zu", index);
  return buf;
}

}  // namespace

City generateCity(const CityParams& params) {
  validate(params);
  City city;
  city.params = params;
  city.params.origin_x = detail::snapMm(params.origin_x);
  city.params.origin_y = detail::snapMm(params.origin_y);
  city.side = detail::snapMm(params.sideMetres());

  detail::StreetNetwork streets = detail::layoutStreets(city.side, params.seed);
  city.river = streets.river;
  city.blocks.reserve(streets.lots.size());
  for (std::size_t i = 0; i < streets.lots.size(); ++i) {
    Block block;
    block.id = blockId(i);
    detail::BlockContent content =
        detail::layoutBlock(streets.lots[i], static_cast<std::uint32_t>(i), block.id, city.params);
    block.kind = content.kind;
    block.lot = std::move(streets.lots[i]);
    block.first_building = static_cast<std::uint32_t>(city.buildings.size());
    block.building_count = static_cast<std::uint32_t>(content.buildings.size());
    for (Building& b : content.buildings) city.buildings.push_back(std::move(b));
    city.blocks.push_back(std::move(block));
  }
  if (params.hills > 0) {
    city.terrain = detail::makeTerrain(city.side, params.seed, params.hills);
    detail::standOnTerrain(city);
  }
  return city;
}

std::size_t cityObjectCount(const City& city) {
  std::size_t count = 0;
  for (const Building& b : city.buildings) count += 1 + b.parts.size();
  return count;
}

}  // namespace urbanpvs::cities
