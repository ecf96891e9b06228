#include "core/Wall.hpp"

#include "core/ConfigRead.hpp"
#include "core/WallKinds.hpp"

namespace rondel {

Wall::Proximity Wall::proximity(Vec2 x) const { return WallKinds::proximity(*this, x); }

void read_wall_motion(const std::vector<double>& rec, std::size_t at, const char* key, Wall& w) {
  if (rec.size() == at + 2) w.velocity = {rec[at], rec[at + 1]};
  if (rec.size() != at + 3) return;
  config::check(rec[at] != 0.0, key, "a rotating wall's omega != 0 (leave 'omega cx cy' out for a fixed wall)",
                config::num(rec[at]));
  w.omega = rec[at];
  w.centre = {rec[at + 1], rec[at + 2]};
}

}  // namespace rondel
