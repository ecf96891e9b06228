#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/Vec2.hpp"

namespace rondel {

// A global wall (every rank has all of them): an infinite line, a segment, or a circle whose inside holds the
// discs (a drum); the kinds are core/WallKinds.hpp's, one file each. A wall translates with a prescribed velocity, or
// rotates about a fixed centre at a constant angular velocity (docs/physics.md sections 1 and 8: a wall is disc 2 with
// R2 -> inf and omega2 = omega).
struct Wall {
  enum class Kind { line, segment, circle };  // the value in a Rondel file (/walls/kind); WallKinds lists them
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
  Vec2 p0;              // a point of the line, or the first end of the segment
  Vec2 p1;              // the second end of a segment (unused for a line)
  Vec2 normal;          // unit normal of a line, pointing to the side where discs live
  Vec2 velocity;        // prescribed translation velocity [m/s] (0 for a rotating wall: its centre is fixed)
  Vec2 centre;          // a circle's centre; the fixed centre of rotation of a rotating line or segment
  double radius = 0.0;  // a circle's radius R_c [m]
  double omega = 0.0;   // angular velocity about `centre` [rad/s], counter-clockwise positive; 0 = no rotation
  double angle = 0.0;   // the angle turned since the start of the run [rad] (the sum of omega dt)
  double lever = 0.0;   // farthest distance from `centre` of a point of the wall that a disc can meet [m]
                        // (segment: an end; line: a corner of the domain; circle: 0, rotation leaves it in place)
  Vec2 displacement_since_build;
  double turn_since_build = 0.0;  // bound of the distance a point of the wall moved by rotation [m]

  // Closest point of the wall to x, and the distance to it (signed for a line: negative behind it).
  struct Proximity {
    double dist;
    Vec2 n;  // unit vector from the disc centre towards the wall (the contact's n, disc 1 -> wall)
  };
  Proximity proximity(Vec2 x) const;
  // The direction of shear_velocity: +x for bottom and top walls, +y for left and right ones.
  Vec2 tangent() const { return (box_side == 1 || box_side == 2) ? Vec2{0.0, 1.0} : Vec2{1.0, 0.0}; }

  bool rotates() const { return omega != 0.0; }
  // The velocity of the wall's surface at the point p (docs/physics.md section 8): v_c + omega z x (p - c).
  Vec2 surface_velocity(Vec2 p) const { return velocity + omega * perp(p - centre); }
  // The largest distance the wall moved since the last neighbour build.
  double moved_since_build() const {
    return std::sqrt(dot(displacement_since_build, displacement_since_build)) + turn_since_build;
  }

  // One step: a translation by velocity dt, or a rotation by omega dt about the centre. A rotation turns
  // the ends (and a line's normal) by the same rotation matrix, computed from omega dt alone: the same bits
  // on every rank and after a restart (the file holds the ends it turns next). A circle only turns `angle`.
  void move(double dt) {
    if (omega == 0.0) {
      const Vec2 dx = dt * velocity;
      p0 += dx;
      p1 += dx;
      displacement_since_build += dx;
      return;
    }
    const double turn = omega * dt;
    angle += turn;
    turn_since_build += std::fabs(turn) * lever;
    if (kind == Kind::circle) return;
    const double c = std::cos(turn), s = std::sin(turn);
    auto rotate = [c, s](Vec2 r) { return Vec2{c * r.x - s * r.y, s * r.x + c * r.y}; };
    p0 = centre + rotate(p0 - centre);
    p1 = centre + rotate(p1 - centre);
    normal = rotate(normal);
  }
};

using WallSet = std::vector<Wall>;

// The optional motion at the end of a line or segment record (numbers from `at` on): none, 'vx vy' (a
// translation) or 'omega cx cy' (a rotation about the fixed centre (cx, cy)). Errors name `key`.
void read_wall_motion(const std::vector<double>& record, std::size_t at, const char* key, Wall& w);

// The sides of the box (walls.box), by Wall::box_side.
inline constexpr const char* kBoxSides[4] = {"bottom", "left", "right", "top"};
// The box_side of the side named `name`; -1 when it is not one.
inline int box_side_index(const std::string& name) {
  for (int k = 0; k < 4; ++k)
    if (name == kBoxSides[k]) return k;
  return -1;
}

}  // namespace rondel
