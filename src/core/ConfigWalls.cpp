// [walls]: line, segment and circle walls (fixed, translating or rotating), the box walls, their motions
// (servo, strain rate, shear) and glue.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/ConfigRead.hpp"

namespace rondel::config {

namespace {

using config::Choice;

// Every number of a wall record must be finite.
void finite_record(const std::vector<double>& rec, const char* key) {
  for (double v : rec) check(std::isfinite(v), key, "finite numbers", num(v));
}

// The optional motion at the end of a line or segment record (numbers from `at` on): none, 'vx vy' (a
// translation) or 'omega cx cy' (a rotation about the fixed centre (cx, cy)).
void read_motion(const std::vector<double>& rec, std::size_t at, const char* key, Wall& w) {
  if (rec.size() == at + 2) w.velocity = {rec[at], rec[at + 1]};
  if (rec.size() != at + 3) return;
  check(rec[at] != 0.0, key, "a rotating wall's omega != 0 (leave 'omega cx cy' out for a fixed wall)", num(rec[at]));
  w.omega = rec[at];
  w.centre = {rec[at + 1], rec[at + 2]};
}

double distance(Vec2 a, Vec2 b) { return std::hypot(a.x - b.x, a.y - b.y); }

void read_wall_records(Config& c) {
  const Domain& d = c.domain;
  for (const auto& rec : c.wall_keys.lines) {
    check(rec.size() == 4 || rec.size() == 6 || rec.size() == 7, "walls.lines",
          "'px py nx ny', 'px py nx ny vx vy' or 'px py nx ny omega cx cy' per wall",
          "a record of " + std::to_string(rec.size()) + " numbers");
    finite_record(rec, "walls.lines");
    Wall w;
    w.kind = Wall::Kind::line;
    w.p0 = {rec[0], rec[1]};
    const double len = std::hypot(rec[2], rec[3]);
    check(len > 0.0, "walls.lines", "a non-zero normal", "normal (0, 0)");
    w.normal = {rec[2] / len, rec[3] / len};
    read_motion(rec, 4, "walls.lines", w);
    if (w.rotates()) {  // the points of the line that discs can meet lie in the domain
      for (Vec2 corner : {Vec2{d.xlo, d.ylo}, Vec2{d.xhi, d.ylo}, Vec2{d.xlo, d.yhi}, Vec2{d.xhi, d.yhi}})
        w.lever = std::max(w.lever, distance(corner, w.centre));
    }
    c.walls.push_back(w);
  }
  for (const auto& rec : c.wall_keys.segments) {
    check(rec.size() == 4 || rec.size() == 6 || rec.size() == 7, "walls.segments",
          "'x1 y1 x2 y2', 'x1 y1 x2 y2 vx vy' or 'x1 y1 x2 y2 omega cx cy' per wall",
          "a record of " + std::to_string(rec.size()) + " numbers");
    finite_record(rec, "walls.segments");
    Wall w;
    w.kind = Wall::Kind::segment;
    w.p0 = {rec[0], rec[1]};
    w.p1 = {rec[2], rec[3]};
    check(rec[0] != rec[2] || rec[1] != rec[3], "walls.segments", "two distinct ends", "a zero-length segment");
    read_motion(rec, 4, "walls.segments", w);
    if (w.rotates()) w.lever = std::max(distance(w.p0, w.centre), distance(w.p1, w.centre));
    c.walls.push_back(w);
  }
  for (const auto& rec : c.wall_keys.circles) {
    check(rec.size() == 3 || rec.size() == 4, "walls.circles", "'cx cy R_c' or 'cx cy R_c omega' per wall",
          "a record of " + std::to_string(rec.size()) + " numbers");
    finite_record(rec, "walls.circles");
    check(rec[2] > 0.0, "walls.circles", "a radius R_c > 0", num(rec[2]));
    Wall w;
    w.kind = Wall::Kind::circle;
    w.centre = w.p0 = {rec[0], rec[1]};
    w.radius = rec[2];
    if (rec.size() == 4) w.omega = rec[3];
    c.walls.push_back(w);
  }
}

void read_box_walls(Config& c) {
  const Domain& d = c.domain;
  const auto& region = c.wall_keys.box_region;
  double b[4] = {d.xlo, d.xhi, d.ylo, d.yhi};
  if (region.size() == 4 && region[0] < region[1] && region[2] < region[3])
    std::copy(region.begin(), region.end(), b);
  else if (!region.empty())
    throw ConfigError("key 'walls.box_region' must be 'xlo xhi ylo yhi' with xlo < xhi and ylo < yhi");
  // Each side's wall: a point, its normal (into the box), and whether it lies across the x direction.
  const struct {
    Vec2 p0, normal;
  } kSide[4] = {{{b[0], b[2]}, {0, 1}}, {{b[0], b[2]}, {1, 0}}, {{b[1], b[2]}, {-1, 0}}, {{b[0], b[3]}, {0, -1}}};
  for (const std::string& side : c.wall_keys.box) {
    const int k = box_side_index(side);  // a side (the validation pass checked the words)
    Wall w;
    w.kind = Wall::Kind::line;
    w.p0 = kSide[k].p0, w.normal = kSide[k].normal, w.box_side = k;
    const bool periodic = kSide[k].normal.x != 0.0 ? d.periodic_x : d.periodic_y;
    check(!periodic, "walls.box", "no wall across a periodic direction", side);
    c.walls.push_back(w);
    c.box_walls.push_back(side);
  }
}

// The box wall named `name` (listed in walls.box); errors name `key` and the `spec` it came from.
Wall& box_wall(Config& c, const std::string& name, const char* key, const std::string& spec) {
  for (Wall& w : c.walls)
    if (w.box_side >= 0 && w.box_side == box_side_index(name)) return w;
  throw ConfigError("key '" + std::string(key) + "': '" + name + "' in '" + spec +
                    "' is not a side listed in walls.box");
}

// The motions of walls.control: 'side:MODE:NUMBER'.
enum class Motion { servo, strain_rate, shear };
constexpr Choice<Motion> kMotions[] = {
    {"servo", Motion::servo}, {"strain_rate", Motion::strain_rate}, {"shear", Motion::shear}};

void read_wall_controls(Config& c) {
  for (const std::string& spec : c.wall_keys.control) {
    const auto a = spec.find(':'), z = spec.rfind(':');
    if (a == std::string::npos || a == z)
      throw ConfigError("key 'walls.control': '" + spec +
                        "' is not 'side:servo:STRESS', 'side:strain_rate:RATE' or 'side:shear:VELOCITY'");
    const std::string name = spec.substr(0, a), mode = spec.substr(a + 1, z - a - 1);
    const auto parsed = numbers(spec.substr(z + 1), "walls.control");
    if (parsed.size() != 1) throw ConfigError("key 'walls.control': '" + spec + "' needs one number after the mode");
    const double value = parsed[0];
    Wall& wall = box_wall(c, name, "walls.control", spec);
    const Choice<Motion>* motion = nullptr;
    for (const Choice<Motion>& m : kMotions)
      if (mode == m.word) motion = &m;
    if (!motion)
      throw ConfigError("key 'walls.control': mode '" + mode + "' in '" + spec + "' is not " +
                        config::choice_words<Motion>(kMotions, false));
    if (motion->value != Motion::shear && wall.control != Wall::Control::velocity)
      throw ConfigError("key 'walls.control': '" + spec + "': wall '" + name +
                        "' already has a servo or strain rate (one per wall)");
    if (motion->value == Motion::servo) {
      check(value > 0.0, "walls.control", "a servo stress > 0 [Pa]", spec);
      wall.control = Wall::Control::servo, wall.target_stress = value;
    } else if (motion->value == Motion::strain_rate) {
      wall.control = Wall::Control::strain_rate, wall.strain_rate = value;
    } else {
      check(std::fabs(value) <= kLightSpeed, "walls.control", "a shear velocity below the speed of light [m/s]", spec);
      wall.shear_velocity = value;
    }
  }
}

}  // namespace

void read_walls(Config& c) {
  read_wall_records(c);
  read_box_walls(c);
  read_wall_controls(c);
  for (const std::string& name : c.wall_keys.rough) box_wall(c, name, "walls.rough", name).rough = true;
}

}  // namespace rondel::config
