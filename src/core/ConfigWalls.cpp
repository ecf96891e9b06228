// [walls]: line, segment and circle walls (fixed, translating or rotating), the box walls, their motions
// (servo, strain rate, shear) and glue.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/ConfigRead.hpp"

namespace rondel::config {

namespace {

const char* const kSides[4] = {"bottom", "left", "right", "top"};

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

void read_wall_records(const Reader& r, Config& c) {
  const Domain& d = c.domain;
  for (const auto& rec : records(r.get<std::string>("walls.lines"), "walls.lines")) {
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
  for (const auto& rec : records(r.get<std::string>("walls.segments"), "walls.segments")) {
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
  for (const auto& rec : records(r.get<std::string>("walls.circles"), "walls.circles")) {
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

void read_box_walls(const Reader& r, Config& c) {
  std::istringstream box(r.get<std::string>("walls.box"));
  std::string side;
  const Domain& d = c.domain;
  const auto region = numbers(r.get<std::string>("walls.box_region"), "walls.box_region");
  double b[4] = {d.xlo, d.xhi, d.ylo, d.yhi};
  if (region.size() == 4 && region[0] < region[1] && region[2] < region[3])
    std::copy(region.begin(), region.end(), b);
  else if (!region.empty())
    throw ConfigError("key 'walls.box_region' must be 'xlo xhi ylo yhi' with xlo < xhi and ylo < yhi");
  while (box >> side) {
    Wall w;
    w.kind = Wall::Kind::line;
    if (side == "bottom")
      w.p0 = {b[0], b[2]}, w.normal = {0, 1}, w.box_side = 0;
    else if (side == "left")
      w.p0 = {b[0], b[2]}, w.normal = {1, 0}, w.box_side = 1;
    else if (side == "right")
      w.p0 = {b[1], b[2]}, w.normal = {-1, 0}, w.box_side = 2;
    else if (side == "top")
      w.p0 = {b[0], b[3]}, w.normal = {0, -1}, w.box_side = 3;
    else
      throw ConfigError("key 'walls.box': '" + side + "' is not a side; allowed: bottom left right top");
    const bool periodic = (side == "left" || side == "right") ? d.periodic_x : d.periodic_y;
    check(!periodic, "walls.box", "no wall across a periodic direction", side);
    c.walls.push_back(w);
    c.box_walls.push_back(side);
  }
}

// The box wall named `name` (listed in walls.box); errors name `key` and the `spec` it came from.
Wall& box_wall(Config& c, const std::string& name, const char* key, const std::string& spec) {
  for (Wall& w : c.walls)
    if (w.box_side >= 0 && name == kSides[w.box_side]) return w;
  throw ConfigError("key '" + std::string(key) + "': '" + name + "' in '" + spec +
                    "' is not a side listed in walls.box");
}

void read_wall_controls(const Reader& r, Config& c) {
  std::istringstream control(r.get<std::string>("walls.control"));
  for (std::string spec; control >> spec;) {
    const auto a = spec.find(':'), z = spec.rfind(':');
    if (a == std::string::npos || a == z)
      throw ConfigError("key 'walls.control': '" + spec +
                        "' is not 'side:servo:STRESS', 'side:strain_rate:RATE' or 'side:shear:VELOCITY'");
    const std::string name = spec.substr(0, a), mode = spec.substr(a + 1, z - a - 1);
    const auto parsed = numbers(spec.substr(z + 1), "walls.control");
    if (parsed.size() != 1) throw ConfigError("key 'walls.control': '" + spec + "' needs one number after the mode");
    const double value = parsed[0];
    Wall& wall = box_wall(c, name, "walls.control", spec);
    if ((mode == "servo" || mode == "strain_rate") && wall.control != Wall::Control::velocity)
      throw ConfigError("key 'walls.control': '" + spec + "': wall '" + name +
                        "' already has a servo or strain rate (one per wall)");
    if (mode == "servo") {
      check(value > 0.0, "walls.control", "a servo stress > 0 [Pa]", spec);
      wall.control = Wall::Control::servo, wall.target_stress = value;
    } else if (mode == "strain_rate") {
      wall.control = Wall::Control::strain_rate, wall.strain_rate = value;
    } else if (mode == "shear") {
      check(std::fabs(value) <= kLightSpeed, "walls.control", "a shear velocity below the speed of light [m/s]", spec);
      wall.shear_velocity = value;
    } else {
      throw ConfigError("key 'walls.control': mode '" + mode + "' in '" + spec +
                        "' is not servo, strain_rate or shear");
    }
  }
}

}  // namespace

void read_walls(const Reader& r, Config& c) {
  read_wall_records(r, c);
  read_box_walls(r, c);
  read_wall_controls(r, c);
  std::istringstream rough(r.get<std::string>("walls.rough"));
  for (std::string name; rough >> name;) box_wall(c, name, "walls.rough", name).rough = true;
  c.rough_depth = r.get<double>("walls.rough_depth");
  non_negative(c.rough_depth, "walls.rough_depth");
  c.servo_gain = r.get<double>("walls.servo_gain");
  check(c.servo_gain > 0.0 && c.servo_gain < 1.0, "walls.servo_gain", "must be in (0, 1)", num(c.servo_gain));
  c.servo_max_speed = r.get<double>("walls.servo_max_speed");
  check(c.servo_max_speed > 0.0, "walls.servo_max_speed", "must be > 0", num(c.servo_max_speed));
}

}  // namespace rondel::config
