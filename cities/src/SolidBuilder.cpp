#include "SolidBuilder.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace urbanpvs::cities::detail {
namespace {

std::int64_t toMm(double v) {
  return std::llround(v * 1000.0);
}

}  // namespace

std::uint32_t SolidBuilder::vertex(Vec2 p, double z) {
  const std::array<std::int64_t, 3> key{toMm(p.x), toMm(p.y), toMm(z)};
  const auto [it, inserted] = index_.try_emplace(key, static_cast<std::uint32_t>(vertices_.size()));
  if (inserted) {
    vertices_.push_back({static_cast<double>(key[0]) / 1000.0, static_cast<double>(key[1]) / 1000.0,
                         static_cast<double>(key[2]) / 1000.0});
  }
  return it->second;
}

void SolidBuilder::addFace(SurfaceType type, const std::vector<std::vector<Vec3>>& rings) {
  Face face;
  face.type = type;
  for (const std::vector<Vec3>& ring : rings) {
    std::vector<std::uint32_t> ids;
    ids.reserve(ring.size());
    for (const Vec3& p : ring) {
      const std::uint32_t id = vertex({p.x, p.y}, p.z);
      if (ids.empty() || ids.back() != id) ids.push_back(id);
    }
    while (ids.size() > 1 && ids.back() == ids.front()) ids.pop_back();
    if (ids.size() < 3) {
      if (face.rings.empty()) return;  // the outer ring collapsed: nothing left of the face
      continue;
    }
    face.rings.push_back(std::move(ids));
  }
  if (!face.rings.empty()) faces_.push_back(std::move(face));
}

void SolidBuilder::addWall(Vec2 a, Vec2 b, double z0, const std::vector<Vec3>& top) {
  std::vector<Vec3> ring{{a.x, a.y, z0}, {b.x, b.y, z0}};
  // Seen from outside (the right of a -> b) this runs along the bottom, then back along the top.
  for (auto it = top.rbegin(); it != top.rend(); ++it) ring.push_back(*it);
  addFace(SurfaceType::Wall, {ring});
}

bool SolidBuilder::isClosed() const {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const Face& face : faces_) {
    for (const auto& ring : face.rings) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        edges.emplace_back(ring[i], ring[(i + 1) % ring.size()]);
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (i + 1 < edges.size() && edges[i] == edges[i + 1]) return false;  // used twice one way
    const std::pair<std::uint32_t, std::uint32_t> reverse{edges[i].second, edges[i].first};
    if (!std::binary_search(edges.begin(), edges.end(), reverse)) return false;
  }
  return !edges.empty();
}

Solid SolidBuilder::release() {
  Solid solid;
  solid.vertices = std::move(vertices_);
  solid.faces = std::move(faces_);
  vertices_.clear();
  index_.clear();
  faces_.clear();
  return solid;
}

void addGround(SolidBuilder& builder, const Polygon& footprint, double z0) {
  std::vector<std::vector<Vec3>> rings;
  auto reversed = [z0](const Ring& ring) {
    std::vector<Vec3> out;
    for (auto it = ring.rbegin(); it != ring.rend(); ++it) out.push_back({it->x, it->y, z0});
    return out;
  };
  rings.push_back(reversed(footprint.outer));
  for (const Ring& hole : footprint.holes) rings.push_back(reversed(hole));
  builder.addFace(SurfaceType::Ground, rings);
}

}  // namespace urbanpvs::cities::detail
