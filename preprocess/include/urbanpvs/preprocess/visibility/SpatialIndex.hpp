// SPDX-License-Identifier: GPL-3.0-or-later
// A quadtree over the boxes of objects or occluders (thesis 5.6.2: whole districts hidden behind
// the cull-map horizon are rejected with one test). Each node knows the box of everything below
// it, its highest point included, so one horizon test of a node decides all its items.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "urbanpvs/geometry/city/Polygon2.hpp"

namespace urbanpvs::preprocess {

class BoxQuadtree {
 public:
  struct Node {
    geometry::Box3 box;  ///< of every item below this node
    std::int32_t child[4] = {-1, -1, -1, -1};
    std::uint32_t first = 0, count = 0;  ///< items stored at this node: items()[first, +count)
    std::uint32_t total = 0;             ///< items in this node's subtree
  };

  BoxQuadtree() = default;
  /// Items are the boxes' indices. Deterministic; `leaf_size` items per leaf at most (unless
  /// they cannot be split further).
  explicit BoxQuadtree(std::span<const geometry::Box3> boxes, std::uint32_t leaf_size = 8);

  const std::vector<Node>& nodes() const { return nodes_; }  ///< nodes()[0] is the root
  const std::vector<std::uint32_t>& items() const { return items_; }
  const geometry::Box3& box(std::uint32_t item) const { return boxes_[item]; }
  std::size_t size() const { return boxes_.size(); }

  /// Visits the tree top-down: `node(id, node) -> bool` decides whether to descend (false:
  /// the whole subtree is skipped), `item(index)` is called for the items of visited nodes.
  template <class NodeFn, class ItemFn>
  void visit(NodeFn&& node, ItemFn&& item) const {
    if (nodes_.empty()) return;
    std::vector<std::uint32_t> stack{0};
    while (!stack.empty()) {
      const std::uint32_t id = stack.back();
      stack.pop_back();
      const Node& n = nodes_[id];
      if (!node(id, n)) continue;
      for (std::uint32_t k = 0; k < n.count; ++k) item(items_[n.first + k]);
      for (int c = 3; c >= 0; --c)
        if (n.child[c] >= 0) stack.push_back(static_cast<std::uint32_t>(n.child[c]));
    }
  }

  /// Calls `item(index)` for every item in the subtree of node `id`.
  template <class ItemFn>
  void for_each_item_below(std::uint32_t id, ItemFn&& item) const {
    const Node& n = nodes_[id];
    for (std::uint32_t k = 0; k < n.count; ++k) item(items_[n.first + k]);
    for (std::int32_t c : n.child)
      if (c >= 0) for_each_item_below(static_cast<std::uint32_t>(c), item);
  }

 private:
  std::vector<geometry::Box3> boxes_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> items_;
};

}  // namespace urbanpvs::preprocess
