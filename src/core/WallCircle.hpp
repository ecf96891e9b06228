#pragma once
// A circle wall whose inside holds the discs (walls.circles 'cx cy R_c [omega]', drums), rotating about its centre
// (docs/physics.md section 8).
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "core/Domain.hpp"
#include "core/Wall.hpp"

namespace rondel {

struct WallCircle {
  static constexpr Wall::Kind kind = Wall::Kind::circle;
  static constexpr const char* name = "circle";
  static constexpr const char* key = "walls.circles";
  static constexpr const char* unit = "m, rad/s";
  static constexpr const char* help =
      "circles 'cx cy R_c [omega]; ...' whose inside holds the discs (drums), rotating about their centre at omega "
      "(default 0)";
  // A record of the key, for the registry's tests (a drum in the unit box, turning).
  static constexpr std::array<double, 4> example{0.5, 0.5, 0.4, 2.0};
  // A disc inside: n from the disc to the rim, dist = R_c - |x - c| (< 0 outside).
  static Wall::Proximity proximity(const Wall& w, Vec2 x) {
    const Vec2 r = x - w.centre;
    const double d = std::sqrt(dot(r, r));
    if (d == 0.0) return {w.radius, {1.0, 0.0}};
    return {w.radius - d, (1.0 / d) * r};
  }
  static Wall read(const std::vector<double>& record, const Domain& domain);
  static std::string behind(const Wall&, double dist) {
    return dist < 0.0 ? "its centre is outside the circle: a circle wall holds discs inside it; walls.circles" : "";
  }
  // One cell per wall: a circle is drawn as its radius at `angle`.
  static void outline(const Wall& w, const WallSet&, const Domain&, std::vector<Vec2>& out) {
    out.push_back(w.centre), out.push_back(w.centre + w.radius * Vec2{std::cos(w.angle), std::sin(w.angle)});
  }
};

}  // namespace rondel
