#pragma once
#include <cstdint>
#include <vector>

#include "core/Vec2.hpp"

namespace rondel {

// A global wall (every rank has all of them): an infinite line or a segment. Walls translate with a
// prescribed velocity and never rotate (docs/physics.md section 1: a wall is disc 2 with R2 -> inf).
struct Wall {
  enum class Kind { line, segment };
  // How the wall moves: a prescribed velocity (0 = fixed); a servo holding a normal stress; or a constant
  // strain rate of the sample between this wall and the opposite box wall.
  enum class Control { velocity, servo, strain_rate };
  Kind kind = Kind::line;
  Control control = Control::velocity;
  double target_stress = 0.0;   // servo: normal stress to hold [Pa] = force / (wall length x thickness)
  double strain_rate = 0.0;     // strain_rate: [1/s], > 0 compresses (the wall moves along its normal)
  int box_side = -1;            // 0 bottom, 1 left, 2 right, 3 top for walls of walls.box; -1 otherwise
  double shear_velocity = 0.0;  // box walls: a velocity along the wall [m/s], +x (bottom, top) or +y (left,
                                // right), added to the servo or strain-rate motion
  int material = 0;             // index into Config::materials (walls.material, walls.materials)
  bool rough = false;           // walls.rough: the discs near it at the start of a stage are glued to it
  // The last step's load from the discs, summed exactly over ranks: total force on the wall, its
  // component against the normal (>= 0 when discs push), and the number of loaded contacts.
  Vec2 force;
  double normal_force = 0.0;
  std::int64_t contacts = 0;
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
  // The direction of shear_velocity: +x for bottom and top walls, +y for left and right ones.
  Vec2 tangent() const { return (box_side == 1 || box_side == 2) ? Vec2{0.0, 1.0} : Vec2{1.0, 0.0}; }

  void move(double dt) {
    const Vec2 dx = dt * velocity;
    p0 += dx;
    p1 += dx;
    displacement_since_build += dx;
  }
};

using WallSet = std::vector<Wall>;

}  // namespace rondel
