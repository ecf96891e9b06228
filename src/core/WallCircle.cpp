#include "core/WallCircle.hpp"

#include "core/ConfigRead.hpp"

namespace rondel {

Wall WallCircle::read(const std::vector<double>& rec, const Domain&) {
  config::check(rec.size() == 3 || rec.size() == 4, key, "'cx cy R_c' or 'cx cy R_c omega' per wall",
                "a record of " + std::to_string(rec.size()) + " numbers");
  config::check(rec[2] > 0.0, key, "a radius R_c > 0", config::num(rec[2]));
  Wall w;
  w.kind = kind;
  w.centre = w.p0 = {rec[0], rec[1]};
  w.radius = rec[2];
  if (rec.size() == 4) w.omega = rec[3];
  return w;
}

}  // namespace rondel
