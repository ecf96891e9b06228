#pragma once
// A segment wall (walls.segments 'x1 y1 x2 y2 [vx vy | omega cx cy]'): discs meet it from either side and at its
// ends.
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/Domain.hpp"
#include "core/Wall.hpp"

namespace rondel {

struct WallSegment {
  static constexpr Wall::Kind kind = Wall::Kind::segment;
  static constexpr const char* name = "segment";
  static constexpr const char* key = "walls.segments";
  static constexpr const char* unit = "m, m/s, rad/s";
  static constexpr const char* help =
      "segments 'x1 y1 x2 y2 [vx vy | omega cx cy]; ...' (a translation or a rotation about the fixed centre (cx, "
      "cy), counter-clockwise positive)";
  // A record of the key, for the registry's tests (moving up).
  static constexpr std::array<double, 6> example{0.2, 0.1, 0.9, 0.2, 0.0, 0.01};
  // The distance to the closest point of the segment, and n towards it.
  static Wall::Proximity proximity(const Wall& w, Vec2 x) {
    const Vec2 e = w.p1 - w.p0;
    double s = dot(x - w.p0, e) / dot(e, e);
    if (s < 0.0) s = 0.0;
    if (s > 1.0) s = 1.0;
    const Vec2 d = (w.p0 + s * e) - x;
    const double dist = std::sqrt(dot(d, d));
    if (dist == 0.0) return {0.0, -perp(e) * (1.0 / std::sqrt(dot(e, e)))};
    return {dist, (1.0 / dist) * d};
  }
  static Wall read(const std::vector<double>& record, const Domain& domain);
  static std::string behind(const Wall&, double) { return ""; }  // a segment has no far side
  static void outline(const Wall& w, const WallSet&, const Domain&, std::vector<Vec2>& out) {
    out.push_back(w.p0), out.push_back(w.p1);
  }
};

}  // namespace rondel
