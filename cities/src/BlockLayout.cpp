// Block layouts after the Vienna model of Wonka's thesis (ch. 5.7): blocks of 1-12 connected
// buildings with extruded footprints, most of them perimeter blocks around a courtyard.
//
// Every layout cuts the lot with straight cuts whose end points are computed once, snapped to
// millimetres and then shared by the two buildings on either side. That is what makes common
// walls bit-identical (a union fuses them) and rules out overlaps: buildings are pieces of a
// partition of the lot, never independently placed shapes.
//
// Shapes, heights and roof kinds come from separate random streams, so a block's footprints and
// eaves heights are the same whatever the roof mode: the LoD2 city is the LoD1 city with roofs.
#include "BlockLayout.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>

#include "Geometry2d.hpp"
#include "Roofs.hpp"
#include "urbanpvs/cities/Random.hpp"

namespace urbanpvs::cities::detail {
namespace {

constexpr std::uint64_t kStreamBlock = 10;
constexpr std::uint64_t kStreamRoof = 11;

constexpr double kStoreyHeight = 3.2;       // metres per storey (Gründerzeit ceilings are high)
constexpr double kTowerStoreyHeight = 3.6;  // office storeys
constexpr double kMaxRoofRise = 8.0;        // highest pitched roof above its eaves, metres
constexpr std::size_t kMaxBuildingsPerBlock = 12;

// Snaps a height to whole centimetres (heights read better; still whole millimetres).
double snapCm(double metres) {
  return std::round(metres * 100.0) / 100.0;
}

int storeys(double eaves, double storey_height) {
  return std::max(1, static_cast<int>(std::floor(eaves / storey_height)));
}

std::string buildingId(const std::string& block_id, std::size_t k) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "-b%02u", static_cast<unsigned>(k));
  return block_id + buf;
}

// Per-block style: neighbouring buildings of one block have similar heights.
struct Style {
  double eaves_base;
  double frontage;  // typical width of a building along the street
};

double pickEaves(Random& rng, const Style& style) {
  if (rng.chance(0.08)) return snapCm(rng.uniform(8.0, 11.0));  // an old low house
  return snapCm(std::clamp(style.eaves_base + rng.uniform(-4.0, 4.0), 8.0, 30.0));
}

// Fields common to every simple building; the solid is set by the caller.
Building simpleBuilding(std::string id, Polygon footprint, double eaves) {
  Building b;
  b.id = std::move(id);
  b.footprint = std::move(footprint);
  b.eaves_height = eaves;
  b.ridge_height = eaves;
  b.roof = RoofKind::Flat;
  b.levels = storeys(eaves, kStoreyHeight);
  return b;
}

void setFlat(Building& b) {
  b.solid = flatSolid(b.footprint, b.ground_z, b.eaves_height);
  b.roof = RoofKind::Flat;
  b.ridge_height = b.eaves_height;
}

void setRoof(Building& b, RoofedSolid&& roofed) {
  b.solid = std::move(roofed.solid);
  b.roof = roofed.roof;
  b.ridge_height = roofed.ridge_height;
}

double highestZ(const Solid& solid) {
  double z = 0.0;
  for (const Vec3& v : solid.vertices) z = std::max(z, v.z);
  return z;
}

// ---------------------------------------------------------------------------------------------
// Perimeter blocks: a ring of buildings of depth 9.5-16 m along the streets around a courtyard.
// The ring is cut perpendicular to the street at every lot boundary; block corners are cut along
// the diagonal from street corner to courtyard corner, and most corner cuts are dropped so that
// corner buildings are L-shaped and front both streets.

struct Cut {
  Vec2 outer;  // on the street line
  Vec2 inner;  // on the courtyard line
  bool corner = false;
  bool active = false;    // separates two buildings
  double position = 0.0;  // arc length along the street line from lot vertex 0
};

std::vector<Cut> ringCuts(const Ring& lot, const Ring& court, const std::vector<double>& depth,
                          const Style& style, Random& rng) {
  std::vector<Cut> cuts;
  const std::size_t n = lot.size();
  double arc = 0.0;
  for (std::size_t s = 0; s < n; ++s) {
    const Vec2 p = lot[s];
    const Vec2 edge = lot[(s + 1) % n] - p;
    const double len = length(edge);
    const Vec2 u = edge * (1.0 / len);
    const Vec2 inward = leftNormal(u);
    cuts.push_back({p, court[s], true, rng.chance(0.2), arc});
    // Admissible cut positions along this side, measured from p: the courtyard end of the cut
    // must stay 3 m from the courtyard corners and the street end 3 m from the street corners.
    const double c0 = dot(court[s] - p, u);
    const double c1 = dot(court[(s + 1) % n] - p, u);
    const double lo = std::max(c0 + 3.0, 3.0);
    const double hi = std::min(c1 - 3.0, len - 3.0);
    for (double a = c0 + style.frontage * rng.uniform(0.5, 1.0); a <= hi;
         a += style.frontage * rng.uniform(0.75, 1.3)) {
      if (a < lo) continue;
      const Vec2 o = p + u * a;
      cuts.push_back({snapMm(o), snapMm(o + inward * depth[s]), false, rng.chance(0.85), arc + a});
    }
    arc += len;
  }
  return cuts;
}

// Drops separating cuts until the block has at most kMaxBuildingsPerBlock buildings, always
// merging the two neighbours with the shortest combined frontage; never leaves exactly one cut
// (a ring cut once would be a building touching itself).
void limitBuildings(std::vector<Cut>& cuts, double perimeter) {
  auto active_indices = [&] {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < cuts.size(); ++i) {
      if (cuts[i].active) idx.push_back(i);
    }
    return idx;
  };
  std::vector<std::size_t> act = active_indices();
  while (act.size() > kMaxBuildingsPerBlock) {
    std::size_t drop = 0;
    double best = 0.0;
    for (std::size_t k = 0; k < act.size(); ++k) {
      const double prev = cuts[act[(k + act.size() - 1) % act.size()]].position;
      const double next = cuts[act[(k + 1) % act.size()]].position;
      double span = next - prev;
      if (span <= 0.0) span += perimeter;
      if (k == 0 || span < best) {
        best = span;
        drop = k;
      }
    }
    cuts[act[drop]].active = false;
    act = active_indices();
  }
  if (act.size() == 1) cuts[(act[0] + cuts.size() / 2) % cuts.size()].active = true;
}

double minSegmentDepth(const Strip& strip) {
  double d = 1e300;
  const std::size_t segments = strip.closed ? strip.outer.size() : strip.outer.size() - 1;
  for (std::size_t k = 0; k < segments; ++k) {
    const std::size_t next = (k + 1) % strip.outer.size();
    const Vec2 dir = normalized(strip.outer[next] - strip.outer[k]);
    d = std::min(d, std::fabs(cross(dir, strip.inner[k] - strip.outer[k])));
  }
  return d;
}

Building stripBuilding(const Strip& strip, std::string id, double eaves, const CityParams& params,
                       Random& roof_rng) {
  Building b = simpleBuilding(std::move(id), stripFootprint(strip), eaves);
  const double slope = roof_rng.uniform(0.55, 1.0);
  const RoofKind wanted = roof_rng.chance(0.4) ? RoofKind::Hipped : RoofKind::Gabled;
  if (params.roofs == RoofMode::Lod2) {
    const double rise = snapCm(std::min(slope * 0.5 * minSegmentDepth(strip), kMaxRoofRise));
    if (auto roofed = stripSolid(strip, b.ground_z, eaves, snapMm(eaves + rise), wanted)) {
      setRoof(b, std::move(*roofed));
      return b;
    }
  }
  setFlat(b);
  return b;
}

std::optional<std::vector<Building>> perimeterBlock(const Ring& lot, const std::string& block_id,
                                                    const CityParams& params, Random& rng,
                                                    Random& roof_rng) {
  const std::size_t n = lot.size();
  const double base_depth = rng.uniform(10.5, 14.0);
  std::vector<double> depth(n);
  for (double& d : depth) d = std::clamp(base_depth + rng.uniform(-1.5, 1.5), 9.5, 16.0);
  std::optional<Ring> court = insetConvex(lot, depth, 6.0);
  if (!court) {  // a short side vanished: try the shallowest ring
    std::fill(depth.begin(), depth.end(), 9.5);
    court = insetConvex(lot, depth, 6.0);
  }
  if (!court) return std::nullopt;
  const Ring court_mm = snapMm(*court);
  if (signedArea(court_mm) < 120.0) return std::nullopt;

  const Style style{rng.uniform(13.0, 24.0), rng.uniform(9.0, 16.0)};
  std::vector<Cut> cuts = ringCuts(lot, court_mm, depth, style, rng);
  if (rng.chance(0.05)) {  // one building around the whole courtyard (a "Hof")
    for (Cut& c : cuts) c.active = false;
  }
  double perimeter = 0.0;
  for (std::size_t s = 0; s < n; ++s) perimeter += length(lot[(s + 1) % n] - lot[s]);
  limitBuildings(cuts, perimeter);

  std::vector<std::size_t> act;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    if (cuts[i].active) act.push_back(i);
  }
  std::vector<Building> out;
  if (act.empty()) {
    Strip ring;
    ring.closed = true;
    for (const Cut& c : cuts) {
      if (!c.corner) continue;
      ring.outer.push_back(c.outer);
      ring.inner.push_back(c.inner);
    }
    out.push_back(
        stripBuilding(ring, buildingId(block_id, 0), pickEaves(rng, style), params, roof_rng));
    return out;
  }
  for (std::size_t k = 0; k < act.size(); ++k) {
    // Stations from one separating cut to the next: the cuts themselves and the block corners
    // in between (cuts that separate nothing are not vertices of the footprint).
    Strip strip;
    const std::size_t end = act[(k + 1) % act.size()];
    for (std::size_t i = act[k];; i = (i + 1) % cuts.size()) {
      if (i == act[k] || i == end || cuts[i].corner) {
        strip.outer.push_back(cuts[i].outer);
        strip.inner.push_back(cuts[i].inner);
      }
      if (i == end && strip.outer.size() > 1) break;
    }
    out.push_back(
        stripBuilding(strip, buildingId(block_id, k), pickEaves(rng, style), params, roof_rng));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Solid blocks: the whole lot built up, cut by parallel cuts into slices that run from street to
// street. Deep slices get a light well (a hole), as Viennese tenements do.

// A light well in the middle of a convex slice, 4 m from every wall, or nothing if none fits.
std::optional<Ring> lightWell(const Ring& slice, Vec2 t, Random& rng) {
  const Vec2 n = leftNormal(t);
  const Vec2 c = snapMm(centroid(slice));
  const double ht = rng.uniform(1.8, 3.0);
  const double hn = rng.uniform(2.0, 4.0);
  const bool wanted = rng.chance(0.6);
  // Clockwise, as holes are.
  Ring well{c - t * ht - n * hn, c - t * ht + n * hn, c + t * ht + n * hn, c + t * ht - n * hn};
  well = snapMm(well);
  for (const Vec2& p : well) {
    if (insideDistance(slice, p) < 4.0) return std::nullopt;
  }
  if (!wanted) return std::nullopt;
  return well;
}

double shortestEdge(const Ring& ring) {
  double best = 1e300;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    best = std::min(best, length(ring[(i + 1) % ring.size()] - ring[i]));
  }
  return best;
}

bool goodSlice(const Ring& slice) {
  return slice.size() >= 3 && signedArea(slice) >= 60.0 && shortestEdge(slice) >= 1.0 &&
         insideDistance(slice, centroid(slice)) >= 3.0;
}

std::vector<Ring> sliceLot(const Ring& lot, Vec2 t, Random& rng) {
  const Extent ext = extentAlong(lot, t);
  const double span = ext.hi - ext.lo;
  const double width = rng.uniform(9.0, 18.0);
  const auto count = static_cast<std::size_t>(
      std::clamp(std::floor(span / width + 0.5), 1.0, static_cast<double>(8)));
  std::vector<Ring> slices;
  Ring rest = lot;
  for (std::size_t k = 1; k < count; ++k) {
    const double at_cut = ext.lo + span * (static_cast<double>(k) + rng.uniform(-0.2, 0.2)) /
                                       static_cast<double>(count);
    // A cut through (nearly) a lot vertex would leave a sliver edge; nudge it once.
    for (const double nudge : {0.0, 1.5}) {
      const std::optional<ConvexSplit> split = splitConvex(rest, t, at_cut + nudge);
      if (split && goodSlice(split->below) && goodSlice(split->above)) {
        slices.push_back(split->below);
        rest = split->above;
        break;
      }
    }
  }
  slices.push_back(rest);
  return slices;
}

// Longer axis of a slice: pitched roofs run their ridge along it (a shorter span, a lower roof).
Vec2 ridgeDirection(const Ring& ring, Vec2 t) {
  const Vec2 n = leftNormal(t);
  const Extent et = extentAlong(ring, t);
  const Extent en = extentAlong(ring, n);
  return (et.hi - et.lo) >= (en.hi - en.lo) ? t : n;
}

void roofSlice(Building& b, Vec2 t, const CityParams& params, Random& roof_rng) {
  const double slope = roof_rng.uniform(0.55, 1.0);
  const bool hipped = roof_rng.chance(0.45);
  if (params.roofs != RoofMode::Lod2) return setFlat(b);
  const Ring& outer = b.footprint.outer;
  if (hipped && b.footprint.holes.empty()) {
    if (auto roofed = hippedSolid(outer, b.ground_z, b.eaves_height, slope, kMaxRoofRise)) {
      roofed->ridge_height = highestZ(roofed->solid) - b.ground_z;
      return setRoof(b, std::move(*roofed));
    }
  }
  const Vec2 dir = ridgeDirection(outer, t);
  const Vec2 n = leftNormal(dir);
  // The ridge passes through the light well, whose centre is the slice's centroid.
  const Vec2 through = b.footprint.holes.empty() ? centroid(outer) : centroid(b.footprint.holes[0]);
  for (const double shift : {0.0, 0.37, -0.41}) {
    const Vec2 p = through + n * shift;
    double reach = 0.0;
    for (const Vec2& v : outer) reach = std::max(reach, std::fabs(dot(n, v - p)));
    const double rise = snapCm(std::min(slope * reach, kMaxRoofRise));
    if (auto roofed = gabledSolid(b.footprint, p, dir, b.ground_z, b.eaves_height,
                                  snapMm(b.eaves_height + rise))) {
      return setRoof(b, std::move(*roofed));
    }
  }
  setFlat(b);
}

std::vector<Building> solidBlock(const Ring& lot, const std::string& block_id,
                                 const CityParams& params, Random& rng, Random& roof_rng) {
  const Vec2 t = longestEdgeDirection(lot);
  const Style style{rng.uniform(13.0, 24.0), 0.0};
  std::vector<Building> out;
  for (const Ring& slice : sliceLot(lot, t, rng)) {
    Polygon fp{slice, {}};
    if (std::optional<Ring> well = lightWell(slice, t, rng)) fp.holes.push_back(std::move(*well));
    Building b =
        simpleBuilding(buildingId(block_id, out.size()), std::move(fp), pickEaves(rng, style));
    roofSlice(b, t, params, roof_rng);
    out.push_back(std::move(b));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Tower blocks: a 40-80 m high-rise in the middle of the lot, on a plaza or on a podium that
// fills the lot (then a composite building: the podium part has the tower's footprint as a hole,
// so the two parts share the tower's walls exactly and never overlap).

std::optional<std::vector<Building>> towerBlock(const Ring& lot, const std::string& block_id,
                                                Random& rng) {
  const Vec2 t = longestEdgeDirection(lot);
  const Vec2 n = leftNormal(t);
  const Vec2 c = snapMm(centroid(lot));
  double ht = rng.uniform(8.0, 13.0);
  double hn = rng.uniform(8.0, 13.0);
  const double height = snapCm(rng.uniform(40.0, 80.0));
  const bool podium = rng.chance(0.5);
  const double podium_height = snapCm(rng.uniform(8.0, 14.0));
  std::optional<Ring> tower;
  for (int attempt = 0; attempt < 4 && !tower; ++attempt) {
    Ring rect = snapMm(
        Ring{c - t * ht - n * hn, c + t * ht - n * hn, c + t * ht + n * hn, c - t * ht + n * hn});
    bool fits = true;
    for (const Vec2& p : rect) fits = fits && insideDistance(lot, p) >= 4.0;
    if (fits) tower = std::move(rect);
    ht *= 0.8;
    hn *= 0.8;
    if (ht < 6.0 || hn < 6.0) break;
  }
  if (!tower) return std::nullopt;

  std::vector<Building> out;
  Building b = simpleBuilding(buildingId(block_id, 0), Polygon{*tower, {}}, height);
  b.levels = storeys(height, kTowerStoreyHeight);
  if (!podium) {
    setFlat(b);
    out.push_back(std::move(b));
    return out;
  }
  b.footprint = Polygon{lot, {}};
  BuildingPart base;
  base.id = b.id + "-p0";
  base.footprint = Polygon{lot, {Ring(tower->rbegin(), tower->rend())}};
  base.eaves_height = base.ridge_height = podium_height;
  base.levels = storeys(podium_height, kStoreyHeight);
  base.solid = flatSolid(base.footprint, b.ground_z, podium_height);
  BuildingPart high;
  high.id = b.id + "-p1";
  high.footprint = Polygon{*tower, {}};
  high.eaves_height = high.ridge_height = height;
  high.levels = b.levels;
  high.solid = flatSolid(high.footprint, b.ground_z, height);
  b.parts.push_back(std::move(base));
  b.parts.push_back(std::move(high));
  out.push_back(std::move(b));
  return out;
}

}  // namespace

BlockContent layoutBlock(const Ring& lot, std::uint32_t block_index, const std::string& block_id,
                         const CityParams& params) {
  Random rng = Random::forStream(params.seed, kStreamBlock, block_index);
  Random roof_rng = Random::forStream(params.seed, kStreamRoof, block_index);
  BlockContent content;
  // Parks ~4%, towers ~2.5%, solid blocks ~18%, perimeter blocks the rest; small lots and lots
  // that cannot hold a courtyard or a tower are built up solid.
  const double u = rng.uniform01();
  const bool small = signedArea(lot) < 900.0;
  if (!small && u < 0.04) {
    content.kind = BlockKind::Park;
    return content;
  }
  std::optional<std::vector<Building>> built;
  if (!small && u < 0.065) {
    built = towerBlock(lot, block_id, rng);
    content.kind = BlockKind::Tower;
  } else if (!small && u >= 0.25) {
    built = perimeterBlock(lot, block_id, params, rng, roof_rng);
    content.kind = BlockKind::Perimeter;
  }
  if (!built) {
    built = solidBlock(lot, block_id, params, rng, roof_rng);
    content.kind = BlockKind::Solid;
  }
  content.buildings = std::move(*built);
  for (Building& b : content.buildings) b.block = block_index;
  return content;
}

}  // namespace urbanpvs::cities::detail
