#pragma once
// An infinite line wall (walls.lines 'px py nx ny [vx vy | omega cx cy]'): a point and a unit normal pointing to
// the side where the discs live; the box walls (walls.box) are lines too.
#include <array>
#include <string>
#include <vector>

#include "core/Domain.hpp"
#include "core/Wall.hpp"

namespace rondel {

struct WallLine {
  static constexpr Wall::Kind kind = Wall::Kind::line;
  static constexpr const char* name = "line";
  static constexpr const char* key = "walls.lines";
  static constexpr const char* unit = "m, m/s, rad/s";
  static constexpr const char* help =
      "infinite lines 'px py nx ny [vx vy | omega cx cy]; ...' (n points to the discs; 'vx vy' translates the line, "
      "'omega cx cy' rotates it about (cx, cy))";
  // A record of the key, for the registry's tests (the unit box's floor, y = 0.1, turning about its middle).
  static constexpr std::array<double, 7> example{0.0, 0.1, 0.0, 1.0, 0.5, 0.5, 0.1};
  // The signed distance (negative behind the line) and n = -normal.
  static Wall::Proximity proximity(const Wall& w, Vec2 x) { return {dot(x - w.p0, w.normal), -w.normal}; }
  static Wall read(const std::vector<double>& record, const Domain& domain);
  // Why a disc whose centre is at `dist` may not start there; "" when it may.
  static std::string behind(const Wall& w, double dist);
  // The piece ParaView draws: the line clipped to the domain and to the discs' side of the other lines.
  static void outline(const Wall& w, const WallSet& walls, const Domain& domain, std::vector<Vec2>& out);
};

}  // namespace rondel
