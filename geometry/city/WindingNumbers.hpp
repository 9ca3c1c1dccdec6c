// SPDX-License-Identifier: GPL-3.0-or-later
// Winding numbers of the faces of a constrained triangulation whose constraints are rings:
// how many rings of each kind contain each face. Used by the view cells (free space = inside a
// region ring, inside no footprint; thesis 5.3) and by ring repair (the inside of a
// self-intersecting ring is where it winds non-zero). Templates over CGAL's
// Constrained_triangulation_plus_2, which remembers which input ring every constrained edge
// came from, also after crossings split it; the face info needs `std::array<int, 2> winding`
// and `bool seen`.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace urbanpvs::geometry::detail {

/// One inserted ring: its constraint, its kind (0 or 1) and +1 when its inside is on its left.
template <class Cdtp>
struct RingConstraint {
  typename Cdtp::Constraint_id id;
  int kind = 0;
  int sign = 1;
};

struct VertexPairHash {
  std::size_t operator()(const std::pair<const void*, const void*>& p) const {
    const auto a = reinterpret_cast<std::uintptr_t>(p.first);
    const auto b = reinterpret_cast<std::uintptr_t>(p.second);
    return std::hash<std::uintptr_t>()(a * 0x9E3779B97F4A7C15ull ^ b);
  }
};

/// For every constrained edge {u, w}: the number of ring edges running u→w minus those running
/// w→u, per kind, with u the vertex at the lower address. Crossing u→w from its left to its
/// right lowers the winding by this.
using NetCrossings =
    std::unordered_map<std::pair<const void*, const void*>, std::array<int, 2>, VertexPairHash>;

template <class Cdtp>
NetCrossings net_crossings(const Cdtp& cdt, const std::vector<RingConstraint<Cdtp>>& rings) {
  NetCrossings net;
  for (const RingConstraint<Cdtp>& r : rings) {
    typename Cdtp::Vertex_handle prev;
    for (typename Cdtp::Vertex_handle v : cdt.vertices_in_constraint(r.id)) {
      if (prev != typename Cdtp::Vertex_handle() && prev != v) {
        const void* a = &*prev;
        const void* b = &*v;
        if (a < b)
          net[{a, b}][static_cast<std::size_t>(r.kind)] += r.sign;
        else
          net[{b, a}][static_cast<std::size_t>(r.kind)] -= r.sign;
      }
      prev = v;
    }
  }
  return net;
}

/// A flood fill from the infinite face (winding 0) that adds the net ring crossings at every
/// constrained edge: afterwards face->info().winding[k] counts the rings of kind k around it.
/// This generalises the "odd nesting level" marking to overlapping, nested and
/// self-intersecting rings.
template <class Cdtp>
void classify_windings(Cdtp& cdt, const std::vector<RingConstraint<Cdtp>>& rings) {
  const NetCrossings net = net_crossings(cdt, rings);
  using Face_handle = typename Cdtp::Face_handle;
  for (Face_handle f : cdt.all_face_handles()) f->info().winding = {0, 0}, f->info().seen = false;
  std::deque<Face_handle> queue{cdt.infinite_face()};
  cdt.infinite_face()->info().seen = true;
  while (!queue.empty()) {
    const Face_handle f = queue.front();
    queue.pop_front();
    for (int i = 0; i < 3; ++i) {
      const Face_handle n = f->neighbor(i);
      if (n->info().seen) continue;
      std::array<int, 2> next = f->info().winding;
      if (f->is_constrained(i)) {
        const void* u = &*f->vertex(Cdtp::ccw(i));  // f lies left of u→w
        const void* w = &*f->vertex(Cdtp::cw(i));
        const bool forward = u < w;
        if (auto it = net.find(forward ? std::make_pair(u, w) : std::make_pair(w, u));
            it != net.end()) {
          const int sign = forward ? 1 : -1;
          next[0] -= sign * it->second[0];
          next[1] -= sign * it->second[1];
        }
      }
      n->info().winding = next;
      n->info().seen = true;
      queue.push_back(n);
    }
  }
}

}  // namespace urbanpvs::geometry::detail
