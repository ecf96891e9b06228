#include "core/WallSegment.hpp"

#include <algorithm>

#include "core/ConfigRead.hpp"

namespace rondel {

Wall WallSegment::read(const std::vector<double>& rec, const Domain&) {
  config::check(rec.size() == 4 || rec.size() == 6 || rec.size() == 7, key,
                "'x1 y1 x2 y2', 'x1 y1 x2 y2 vx vy' or 'x1 y1 x2 y2 omega cx cy' per wall",
                "a record of " + std::to_string(rec.size()) + " numbers");
  Wall w;
  w.kind = kind;
  w.p0 = {rec[0], rec[1]};
  w.p1 = {rec[2], rec[3]};
  config::check(rec[0] != rec[2] || rec[1] != rec[3], key, "two distinct ends", "a zero-length segment");
  read_wall_motion(rec, 4, key, w);
  if (w.rotates())
    w.lever = std::max(std::hypot(w.p0.x - w.centre.x, w.p0.y - w.centre.y),
                       std::hypot(w.p1.x - w.centre.x, w.p1.y - w.centre.y));
  return w;
}

}  // namespace rondel
