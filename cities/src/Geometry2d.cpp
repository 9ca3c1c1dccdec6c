#include "Geometry2d.hpp"

#include <cstddef>

namespace urbanpvs::cities::detail {

Ring snapMm(const Ring& ring) {
  Ring out;
  out.reserve(ring.size());
  for (const Vec2& p : ring) out.push_back(snapMm(p));
  return out;
}

double signedArea(const Ring& ring) {
  double twice = 0.0;
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) twice += cross(ring[i], ring[(i + 1) % n]);
  return twice * 0.5;
}

Vec2 centroid(const Ring& ring) {
  // Relative to the first vertex: keeps the products small and the result well conditioned.
  const Vec2 o = ring.front();
  double a = 0.0;
  Vec2 c{0.0, 0.0};
  const std::size_t n = ring.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = ring[i] - o;
    const Vec2 q = ring[(i + 1) % n] - o;
    const double w = cross(p, q);
    a += w;
    c = c + (p + q) * w;
  }
  if (a == 0.0) return o;
  return o + c * (1.0 / (3.0 * a));
}

Ring clipHalfPlane(const Ring& ring, Vec2 n, double c) {
  Ring out;
  const std::size_t count = ring.size();
  for (std::size_t i = 0; i < count; ++i) {
    const Vec2 a = ring[i];
    const Vec2 b = ring[(i + 1) % count];
    const double da = dot(n, a) - c;
    const double db = dot(n, b) - c;
    if (da >= 0.0) out.push_back(a);
    if ((da >= 0.0) != (db >= 0.0)) out.push_back(a + (b - a) * (da / (da - db)));
  }
  return out;
}

std::optional<ConvexSplit> splitConvex(const Ring& ring, Vec2 n, double c) {
  const std::size_t count = ring.size();
  std::vector<double> d(count);
  bool any_below = false;
  bool any_above = false;
  for (std::size_t i = 0; i < count; ++i) {
    d[i] = dot(n, ring[i]) - c;
    any_below = any_below || d[i] < 0.0;
    any_above = any_above || d[i] > 0.0;
  }
  if (!any_below || !any_above) return std::nullopt;
  ConvexSplit split;
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t j = (i + 1) % count;
    if (d[i] < 0.0) split.below.push_back(ring[i]);
    if (d[i] > 0.0) split.above.push_back(ring[i]);
    if (d[i] == 0.0) {  // the line passes through a vertex: it belongs to both halves
      split.below.push_back(ring[i]);
      split.above.push_back(ring[i]);
    }
    if ((d[i] < 0.0 && d[j] > 0.0) || (d[i] > 0.0 && d[j] < 0.0)) {
      const Vec2 x = snapMm(ring[i] + (ring[j] - ring[i]) * (d[i] / (d[i] - d[j])));
      split.below.push_back(x);
      split.above.push_back(x);
    }
  }
  return split;
}

namespace {

// Intersection of the lines p + s*u and q + t*v; nullopt when (nearly) parallel.
std::optional<Vec2> intersectLines(Vec2 p, Vec2 u, Vec2 q, Vec2 v) {
  const double den = cross(u, v);
  if (std::fabs(den) < 1e-9) return std::nullopt;
  const double s = cross(q - p, v) / den;
  return p + u * s;
}

}  // namespace

std::optional<Ring> insetConvex(const Ring& ring, const std::vector<double>& depth,
                                double min_edge) {
  const std::size_t n = ring.size();
  std::vector<Vec2> dir(n);
  std::vector<Vec2> base(n);
  for (std::size_t i = 0; i < n; ++i) {
    dir[i] = normalized(ring[(i + 1) % n] - ring[i]);
    base[i] = ring[i] + leftNormal(dir[i]) * depth[i];
  }
  Ring out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t prev = (i + n - 1) % n;
    // Nearly parallel neighbours make the corner point jump far for a tiny change of angle.
    if (cross(dir[prev], dir[i]) < 0.05) return std::nullopt;
    const auto corner = intersectLines(base[prev], dir[prev], base[i], dir[i]);
    if (!corner) return std::nullopt;
    out[i] = *corner;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e = out[(i + 1) % n] - out[i];
    if (dot(e, dir[i]) < min_edge) return std::nullopt;  // shrunk away or flipped
  }
  return out;
}

Ring simplifyConvex(Ring ring, double min_edge, double min_sin_turn) {
  bool changed = true;
  while (changed && ring.size() > 3) {
    changed = false;
    const std::size_t n = ring.size();
    // Remove the single worst vertex per pass, the one cutting off the smallest triangle, so the
    // outcome does not depend on where the ring happens to start.
    std::size_t worst = n;
    double worst_area = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 a = ring[(i + n - 1) % n];
      const Vec2 b = ring[i];
      const Vec2 c = ring[(i + 1) % n];
      const double la = length(b - a);
      const double lc = length(c - b);
      const double sin_turn = cross(b - a, c - b) / (la * lc);
      const bool bad = la < min_edge || lc < min_edge || sin_turn < min_sin_turn;
      if (!bad) continue;
      const double cut = std::fabs(cross(b - a, c - a));
      if (worst == n || cut < worst_area) {
        worst = i;
        worst_area = cut;
      }
    }
    if (worst != n) {
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(worst));
      changed = true;
    }
  }
  return ring;
}

double insideDistance(const Ring& convex, Vec2 p) {
  double best = 0.0;
  const std::size_t n = convex.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = convex[i];
    const Vec2 d = normalized(convex[(i + 1) % n] - a);
    const double dist = cross(d, p - a);
    if (i == 0 || dist < best) best = dist;
  }
  return best;
}

Extent extentAlong(const Ring& ring, Vec2 dir) {
  Extent e{dot(dir, ring.front()), dot(dir, ring.front())};
  for (const Vec2& p : ring) {
    const double t = dot(dir, p);
    if (t < e.lo) e.lo = t;
    if (t > e.hi) e.hi = t;
  }
  return e;
}

Vec2 longestEdgeDirection(const Ring& ring) {
  const std::size_t n = ring.size();
  std::size_t best = 0;
  double best_len = -1.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double l = length(ring[(i + 1) % n] - ring[i]);
    if (l > best_len) {
      best = i;
      best_len = l;
    }
  }
  return normalized(ring[(best + 1) % n] - ring[best]);
}

bool isStrictlyConvex(const Ring& ring) {
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a = ring[i];
    const Vec2 b = ring[(i + 1) % n];
    const Vec2 c = ring[(i + 2) % n];
    if (cross(b - a, c - b) <= 0.0) return false;
  }
  return true;
}

}  // namespace urbanpvs::cities::detail
