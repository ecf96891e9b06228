#pragma once
#include "core/Vec2.hpp"

namespace rondel {

// The simulation box. Periodic directions wrap positions and use the minimum image; the others only
// bound the cell grid (walls keep the discs in).
struct Domain {
  double xlo = 0.0, xhi = 1.0, ylo = 0.0, yhi = 1.0;
  bool periodic_x = false;
  bool periodic_y = false;

  double length_x() const { return xhi - xlo; }
  double length_y() const { return yhi - ylo; }

  // d = x2 - x1 with the minimum-image correction, formed the same way on every rank.
  Vec2 separation(Vec2 x1, Vec2 x2) const {
    Vec2 d = x2 - x1;
    if (periodic_x) {
      const double L = length_x();
      if (d.x > 0.5 * L)
        d.x -= L;
      else if (d.x < -0.5 * L)
        d.x += L;
    }
    if (periodic_y) {
      const double L = length_y();
      if (d.y > 0.5 * L)
        d.y -= L;
      else if (d.y < -0.5 * L)
        d.y += L;
    }
    return d;
  }

  void wrap(Vec2& x) const {
    if (periodic_x) {
      if (x.x >= xhi)
        x.x -= length_x();
      else if (x.x < xlo)
        x.x += length_x();
    }
    if (periodic_y) {
      if (x.y >= yhi)
        x.y -= length_y();
      else if (x.y < ylo)
        x.y += length_y();
    }
  }

  bool contains(Vec2 x) const { return x.x >= xlo && x.x <= xhi && x.y >= ylo && x.y <= yhi; }
};

}  // namespace rondel
