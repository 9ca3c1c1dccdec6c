// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/SpatialIndex.hpp"

#include <algorithm>

namespace urbanpvs::preprocess {
namespace {

using geometry::Box2;
using geometry::Vec2;

// Items are pushed down to the quadrant that contains their box's centre; a node's box is then
// grown to its items' boxes. Boxes of siblings may overlap, which the visitors allow.
struct Builder {
  std::span<const geometry::Box3> boxes;
  std::uint32_t leaf_size;
  std::vector<BoxQuadtree::Node>& nodes;
  std::vector<std::uint32_t>& items;

  std::int32_t build(std::vector<std::uint32_t>& ids, const Box2& area, int depth) {
    const auto id = static_cast<std::int32_t>(nodes.size());
    nodes.emplace_back();
    geometry::Box3 box;
    for (std::uint32_t i : ids) box.extend(boxes[i]);
    const auto total = static_cast<std::uint32_t>(ids.size());
    if (ids.size() <= leaf_size || depth >= 24) {
      BoxQuadtree::Node& n = nodes[static_cast<std::size_t>(id)];
      n.box = box;
      n.first = static_cast<std::uint32_t>(items.size());
      n.count = total;
      n.total = total;
      items.insert(items.end(), ids.begin(), ids.end());
      return id;
    }
    const Vec2 mid{0.5 * (area.min.x + area.max.x), 0.5 * (area.min.y + area.max.y)};
    std::vector<std::uint32_t> part[4];
    for (std::uint32_t i : ids) {
      const Box2& b = boxes[i].xy;
      const int q = (0.5 * (b.min.x + b.max.x) >= mid.x ? 1 : 0) +
                    (0.5 * (b.min.y + b.max.y) >= mid.y ? 2 : 0);
      part[q].push_back(i);
    }
    ids.clear();
    ids.shrink_to_fit();
    std::int32_t child[4];
    for (int q = 0; q < 4; ++q) {
      const Box2 sub{{(q & 1) ? mid.x : area.min.x, (q & 2) ? mid.y : area.min.y},
                     {(q & 1) ? area.max.x : mid.x, (q & 2) ? area.max.y : mid.y}};
      child[q] = part[q].empty() ? -1 : build(part[q], sub, depth + 1);
    }
    BoxQuadtree::Node& n = nodes[static_cast<std::size_t>(id)];
    n.box = box;
    n.total = total;
    std::copy(child, child + 4, n.child);
    return id;
  }
};

}  // namespace

BoxQuadtree::BoxQuadtree(std::span<const geometry::Box3> boxes, std::uint32_t leaf_size)
    : boxes_(boxes.begin(), boxes.end()) {
  if (boxes_.empty()) return;
  std::vector<std::uint32_t> ids(boxes_.size());
  Box2 area;
  for (std::uint32_t i = 0; i < ids.size(); ++i) ids[i] = i, area.extend(boxes_[i].xy);
  Builder{boxes_, std::max<std::uint32_t>(1, leaf_size), nodes_, items_}.build(ids, area, 0);
}

}  // namespace urbanpvs::preprocess
