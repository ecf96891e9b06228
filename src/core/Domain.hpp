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

  // d = x2 - x1 with the minimum-image correction, formed the same way on every rank (MinimumImage).
  Vec2 separation(Vec2 x1, Vec2 x2) const;

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

// The minimum-image separation of a domain with its lengths computed once, for loops over many pairs (the
// contact kernel): d = x2 - x1, then in a periodic direction of length L, d -= L when d > L/2 and d += L
// when d < -L/2. Domain::separation is this, so every caller forms the same bits.
struct MinimumImage {
  double Lx, Ly, half_x, half_y;
  bool periodic_x, periodic_y;
  explicit MinimumImage(const Domain& d)
      : Lx(d.length_x()),
        Ly(d.length_y()),
        half_x(0.5 * Lx),
        half_y(0.5 * Ly),
        periodic_x(d.periodic_x),
        periodic_y(d.periodic_y) {}
  Vec2 separation(Vec2 x1, Vec2 x2) const {
    Vec2 d = x2 - x1;
    if (periodic_x) {
      if (d.x > half_x)
        d.x -= Lx;
      else if (d.x < -half_x)
        d.x += Lx;
    }
    if (periodic_y) {
      if (d.y > half_y)
        d.y -= Ly;
      else if (d.y < -half_y)
        d.y += Ly;
    }
    return d;
  }
};

inline Vec2 Domain::separation(Vec2 x1, Vec2 x2) const { return MinimumImage(*this).separation(x1, x2); }

// |x - x0|^2 by the minimum image: the squared displacement of a disc from x0 to x.
inline double squared_displacement(const MinimumImage& image, Vec2 x0, Vec2 x) {
  const Vec2 d = image.separation(x0, x);
  return dot(d, d);
}

}  // namespace rondel
