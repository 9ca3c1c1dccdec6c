// SPDX-License-Identifier: GPL-3.0-or-later
#include "urbanpvs/preprocess/visibility/CellMapRenderer.hpp"

#include "urbanpvs/preprocess/visibility/OsMesaCullMapRenderer.hpp"

namespace urbanpvs::preprocess {
namespace {

class CpuCellMapRenderer final : public CellMapRenderer {
 public:
  explicit CpuCellMapRenderer(OccluderSkipping skipping) : skipping_(skipping) {}
  CullMap render(const CullMapGrid& grid, std::span<const Vec3> samples,
                 std::span<const geometry::Occluder* const> occluders,
                 CullMapStats* stats) override {
    return cell_cull_map(grid, samples, occluders, stats, skipping_);
  }

 private:
  OccluderSkipping skipping_;
};

class OsMesaCellMapRenderer final : public CellMapRenderer {
 public:
  OsMesaCellMapRenderer(double zlo, double zhi) : zlo_(zlo), zhi_(zhi) {}
  CullMap render(const CullMapGrid& grid, std::span<const Vec3> samples,
                 std::span<const geometry::Occluder* const> occluders,
                 CullMapStats* stats) override {
    return gl_.cell_cull_map(grid, samples, occluders, zlo_, zhi_, stats);
  }

 private:
  OsMesaCullMapRenderer gl_;
  double zlo_, zhi_;
};

}  // namespace

std::unique_ptr<CellMapRenderer> make_cell_map_renderer(Backend backend, double zlo, double zhi,
                                                        OccluderSkipping skipping) {
  if (backend == Backend::OsMesa) return std::make_unique<OsMesaCellMapRenderer>(zlo, zhi);
  return std::make_unique<CpuCellMapRenderer>(skipping);
}

}  // namespace urbanpvs::preprocess
