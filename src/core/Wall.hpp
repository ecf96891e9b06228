#pragma once
#include <vector>

#include "core/Vec2.hpp"

namespace rondel {

// A global wall (every rank has all of them): an infinite line or a segment. Walls translate with a
// prescribed velocity and never rotate (PHYSICS.md section 1: a wall is disc 2 with R2 -> inf).
struct Wall {
  enum class Kind { line, segment };
  Kind kind = Kind::line;
  Vec2 p0;        // a point of the line, or the first end of the segment
  Vec2 p1;        // the second end of a segment (unused for a line)
  Vec2 normal;    // unit normal of a line, pointing to the side where discs live
  Vec2 velocity;  // prescribed translation velocity [m/s]
  Vec2 displacement_since_build;

  // Closest point of the wall to x, and the distance to it (signed for a line: negative behind it).
  struct Proximity {
    double dist;
    Vec2 n;  // unit vector from the disc centre towards the wall (the contact's n, disc 1 -> wall)
  };
  Proximity proximity(Vec2 x) const;

  void move(double dt) {
    const Vec2 dx = dt * velocity;
    p0 += dx;
    p1 += dx;
    displacement_since_build += dx;
  }
};

using WallSet = std::vector<Wall>;

}  // namespace rondel
