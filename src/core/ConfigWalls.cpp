// [walls]: line, segment and circle walls (fixed, translating or rotating), the box walls, their motions
// (servo, strain rate, shear) and glue.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/WallKinds.hpp"

namespace rondel::config {

namespace {

using config::Choice;

// The walls of every kind's records (walls.lines, walls.segments, walls.circles), in the order of the kinds.
void read_wall_records(Config& c) {
  c.wall_keys.records.resize(WallKinds::size);
  WallKinds::each([&c]<class K>() {
    for (const auto& record : c.wall_keys.records[static_cast<std::size_t>(K::kind)])
      c.walls.push_back(K::read(record, c.domain));
  });
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
    w.kind = WallLine::kind;
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
  // A deforming cell is periodic both ways: nothing bounds it, and a wall would not follow its images.
  if (c.cell_deforms() && !c.walls.empty()) {
    const char* key = !c.wall_keys.box.empty() ? "walls.box" : "walls.lines, walls.segments or walls.circles";
    check(false, key, "no wall inside a deforming periodic cell (a cell.rate_* or cell.stress_* not 0)",
          std::to_string(c.walls.size()) + " wall(s)");
  }
}

}  // namespace rondel::config
