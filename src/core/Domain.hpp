#pragma once
// The simulation box: a periodic cell that may deform (docs/physics.md section 10). Its vectors are a = (L_x, 0)
// and b = (tilt, L_y) from the corner x0 = (xlo, ylo); images of a disc are at x + i a + j b. A box that does not
// deform is this cell with tilt 0 and no rates: one type. Periodic directions wrap positions and use the minimum
// image; the others only bound the cell grid (walls keep the discs in). The type owns the minimum image (with the
// image's velocity in a moving cell), the wrap of a position (with the matching shift of its velocity), the
// deformation and the flip. The [cell] keys (cell.rate_*, cell.stress_*) set the run's rates.
#include <cmath>
#include <stdexcept>

#include "core/Vec2.hpp"

namespace rondel {

// The cell's velocity gradient L (dh/dt = L h), components xx, xy, yy [1/s].
struct CellGradient {
  double xx = 0.0, xy = 0.0, yy = 0.0;
  bool any() const { return xx != 0.0 || xy != 0.0 || yy != 0.0; }
  // The Frobenius norm, a bound of |L v| / |v|.
  double norm() const { return std::sqrt(xx * xx + xy * xy + yy * yy); }
  // L v
  Vec2 of(Vec2 v) const { return {xx * v.x + xy * v.y, yy * v.y}; }
};

struct Domain {
  double xlo = 0.0, xhi = 1.0, ylo = 0.0, yhi = 1.0;
  bool periodic_x = false;
  bool periodic_y = false;
  double tilt = 0.0;   // h_xy, the x component of b [m]; |tilt| <= L_x/2 (flip)
  CellGradient L{};    // the cell's velocity gradient now
  Vec2 va{}, vb{};     // da/dt and db/dt = L a, L b (rates())
  double slope = 0.0;  // tilt / L_y (rates(): after any change of the tilt or of L_y)
  bool moving = false;

  double length_x() const { return xhi - xlo; }
  double length_y() const { return yhi - ylo; }
  Vec2 corner() const { return {xlo, ylo}; }
  // The x offset of the cell's left side at height y (0 for a cell without tilt).
  double shear_shift(double y) const { return tilt == 0.0 ? 0.0 : (y - ylo) * slope; }
  // The mean flow's velocity at x, L (x - x0).
  Vec2 flow(Vec2 x) const { return L.of(x - corner()); }

  // d = x2 - x1 with the minimum-image correction, formed the same way on every rank (MinimumImage, ShearedImage).
  Vec2 separation(Vec2 x1, Vec2 x2) const;

  // A position back into the cell (one lattice vector at most: a disc moves less than a cell per step), and in a
  // moving cell its velocity by the cell's, v -= i da/dt + j db/dt (Lees-Edwards). y first, then x. Returns
  // whether the velocity changed.
  [[gnu::always_inline]] bool wrap(Vec2& x, Vec2& v) const {
    if (standing()) {
      wrap_standing(x);
      return false;
    }
    bool shifted = false;
    if (periodic_y) {
      if (x.y >= yhi) {
        x.y -= length_y();
        if (tilt != 0.0) x.x -= tilt;
        if (moving) v -= vb, shifted = true;
      } else if (x.y < ylo) {
        x.y += length_y();
        if (tilt != 0.0) x.x += tilt;
        if (moving) v += vb, shifted = true;
      }
    }
    if (periodic_x) {
      const double shift = shear_shift(x.y);
      if (x.x - shift >= xhi) {
        x.x -= length_x();
        if (moving) v -= va, shifted = true;
      } else if (x.x - shift < xlo) {
        x.x += length_x();
        if (moving) v += va, shifted = true;
      }
    }
    return shifted;
  }
  // wrap(x, v) of a disc of mass m, and the kinetic energy the shift of its velocity changed (the cell's work).
  [[gnu::always_inline]] double wrap_work(Vec2& x, Vec2& v, double m) const {
    const Vec2 before = v;
    if (!wrap(x, v)) [[likely]]
      return 0.0;
    return 0.5 * m * (dot(v, v) - dot(before, before));
  }
  // wrap_work of a disc of a moving cell (periodic both ways), added to W, for the drift's loop: a disc inside
  // the cell, by far the most, costs one test of its reduced coordinates and adds nothing; the others take
  // wrap_work (the same bits).
  [[gnu::always_inline]] void wrap_moving(Vec2& x, Vec2& v, double m, double& W) const {
    const double sx = x.x - (x.y - ylo) * slope;  // shear_shift(y) without its test (0 when slope is 0)
    if (!(x.y >= ylo && x.y < yhi && sx >= xlo && sx < xhi)) [[unlikely]]
      W += wrap_work(x, v, m);
  }
  // The same without a velocity (a cell that does not move, or a position alone).
  void wrap(Vec2& x) const {
    Vec2 v;
    wrap(x, v);
  }
  // A cell that neither tilts nor moves: its x and y wrap apart, and no velocity changes.
  bool standing() const { return tilt == 0.0 && !moving; }
  void wrap_standing(Vec2& x) const {
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

  // x inside the cell (its sides included).
  bool contains(Vec2 x) const {
    const double sx = x.x - shear_shift(x.y);
    return sx >= xlo && sx <= xhi && x.y >= ylo && x.y <= yhi;
  }

  // The shape of `other` (corner, lengths, tilt), this cell's rates and periodic flags kept.
  void take_shape(const Domain& other) {
    xlo = other.xlo, xhi = other.xhi, ylo = other.ylo, yhi = other.yhi, tilt = other.tilt;
    rates();
  }
  // da/dt and db/dt from the gradient and the present h.
  void rates() {
    va = {L.xx * length_x(), 0.0};
    vb = {L.xx * tilt + L.xy * length_y(), L.yy * length_y()};
    slope = tilt / length_y();
    moving = L.any();
  }
  // h += dt L h, the corner fixed (the same arithmetic on every rank).
  void deform(double dt) {
    if (!moving) return;
    xhi += dt * va.x;
    tilt += dt * vb.x;
    yhi += dt * vb.y;
    rates();
  }
  // b -= sign(tilt) a when |tilt| passes L_x/2: the same lattice (the same contacts and forces), other labels of
  // the images. Returns +1 when the tilt fell by L_x, -1 when it rose, 0 when it did not flip.
  int flip() {
    const double half = 0.5 * length_x();
    int sign = 0;
    if (tilt > half)
      tilt -= length_x(), sign = 1;
    else if (tilt < -half)
      tilt += length_x(), sign = -1;
    else
      return 0;
    rates();
    return sign;
  }
};

// The minimum-image separation of a cell that neither tilts nor moves, its lengths computed once, for loops over
// many pairs (the contact kernel, the neighbour search): d = x2 - x1, then d_x -= L_x when d_x > L_x/2 and
// d_x += L_x when d_x < -L_x/2 in a periodic x, the same in y. The standing box pays for nothing else; a cell
// that tilts or moves has ShearedImage (the same bits when tilt = 0 and nothing moves: the corrections of x and
// y are then independent). Constructing one from a tilted or moving cell is a programming error.
struct MinimumImage {
  double Lx, Ly, half_x, half_y;
  bool periodic_x, periodic_y;
  explicit MinimumImage(const Domain& d)
      : Lx(d.length_x()),
        Ly(d.length_y()),
        half_x(0.5 * Lx),
        half_y(0.5 * Ly),
        periodic_x(d.periodic_x),
        periodic_y(d.periodic_y) {
    if (!d.standing()) throw std::logic_error("MinimumImage of a tilted or moving cell: use ShearedImage");
  }
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
  // The same; a standing cell's images move with their discs (no velocity offset).
  static constexpr bool kMoving = false;
  Vec2 separation(Vec2 x1, Vec2 x2, Vec2& /*dv*/) const { return separation(x1, x2); }
};

// No image: the wall rows of the contact kernel, whose pass forms no pair separation.
struct NoImage {
  explicit NoImage(const Domain&) {}
};

// The minimum image of the deforming cell (docs/physics.md section 10), periodic both ways: d = x2 - x1, then
// d -= b when d_y > L_y/2 and d += b when d_y < -L_y/2, then d_x -= L_x when d_x > L_x/2 and d_x += L_x when
// d_x < -L_x/2; one lattice vector each way suffices for positions in the cell with |tilt| <= L_x/2. It also adds
// to `dv` the velocity offset of disc 2's image, j db/dt + i da/dt (Lees-Edwards): the image moves at v2 + dv.
// Its fields are few (the contact kernel's loop is short of registers).
struct ShearedImage {
  double Lx, Ly, half_x, half_y, tilt, va_x;
  Vec2 vb;
  explicit ShearedImage(const Domain& d)
      : Lx(d.length_x()), Ly(d.length_y()), half_x(0.5 * Lx), half_y(0.5 * Ly), tilt(d.tilt), va_x(d.va.x), vb(d.vb) {
    // A cell that tilts or moves is periodic both ways (the configuration refuses rates otherwise).
    if (!d.periodic_x || !d.periodic_y) throw std::logic_error("ShearedImage of a cell that is not periodic both ways");
  }
  static constexpr bool kMoving = true;
  // (In a cell that does not move, da/dt and db/dt are zero: dv stays zero.) `crossed()` is called when the pair
  // is across the boundary (once or twice: for y and for x), in the branches that shift it.
  template <class Crossed>
  [[gnu::always_inline]] Vec2 separation(Vec2 x1, Vec2 x2, Vec2& dv, Crossed&& crossed) const {
    Vec2 d = x2 - x1;
    if (d.y > half_y) {
      d.y -= Ly;
      d.x -= tilt;
      dv -= vb;
      crossed();
    } else if (d.y < -half_y) {
      d.y += Ly;
      d.x += tilt;
      dv += vb;
      crossed();
    }
    if (d.x > half_x) {
      d.x -= Lx;
      dv.x -= va_x;
      crossed();
    } else if (d.x < -half_x) {
      d.x += Lx;
      dv.x += va_x;
      crossed();
    }
    return d;
  }
  [[gnu::always_inline]] Vec2 separation(Vec2 x1, Vec2 x2, Vec2& dv) const {
    return separation(x1, x2, dv, [] {});
  }
  Vec2 separation(Vec2 x1, Vec2 x2) const {
    Vec2 dv;
    return separation(x1, x2, dv);
  }
};

inline Vec2 Domain::separation(Vec2 x1, Vec2 x2) const {
  return standing() ? MinimumImage(*this).separation(x1, x2) : ShearedImage(*this).separation(x1, x2);
}

// |x - x0|^2 by the minimum image: the squared displacement of a disc from x0 to x.
inline double squared_displacement(const MinimumImage& image, Vec2 x0, Vec2 x) {
  const Vec2 d = image.separation(x0, x);
  return dot(d, d);
}

}  // namespace rondel
