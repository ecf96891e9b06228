#include "core/Wall.hpp"

#include <cmath>

namespace rondel {

Wall::Proximity Wall::proximity(Vec2 x) const {
  if (kind == Kind::line) return {dot(x - p0, normal), -normal};
  if (kind == Kind::circle) {  // a disc inside: n from the disc to the rim, dist = R_c - |x - c| (< 0 outside)
    const Vec2 r = x - centre;
    const double d = std::sqrt(dot(r, r));
    if (d == 0.0) return {radius, {1.0, 0.0}};
    return {radius - d, (1.0 / d) * r};
  }
  const Vec2 e = p1 - p0;
  double s = dot(x - p0, e) / dot(e, e);
  if (s < 0.0) s = 0.0;
  if (s > 1.0) s = 1.0;
  const Vec2 d = (p0 + s * e) - x;
  const double dist = std::sqrt(dot(d, d));
  if (dist == 0.0) return {0.0, -perp(e) * (1.0 / std::sqrt(dot(e, e)))};
  return {dist, (1.0 / dist) * d};
}

}  // namespace rondel
