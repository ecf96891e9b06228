#pragma once
// The cell's work of the contact rows across a moving cell's boundary, for the contact kernel (docs/physics.md
// section 10). Across that boundary the kernel's works are of the motion relative to disc 2's image, and the discs
// themselves receive dv . (f1' + f1) more, dv the velocity offset of the image: the cell's work W_cell. The kernel's
// pass notes these rows (the few at the boundary, in the image's branches that shift them) with the last step's
// forces, and books them after its loop, in row order: the same sums as booking them in the loop, without a test
// of dv in every row (which kept dv live through every row's laws: 7 % more instructions in the pass).
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/Vec2.hpp"
#include "physics/ContactKinematics.hpp"

namespace rondel {

struct Crossing {
  std::size_t r;
  double F_n, F_t;  // the last step's
};
using Crossings = std::vector<Crossing>;

// Row r is across the boundary (noted once, however many of the image's branches shift it).
[[gnu::noinline, gnu::cold]] inline void note_crossing(Crossings& crossings, std::size_t r, const ContactTable& tab) {
  if (crossings.empty() || crossings.back().r != r) crossings.push_back({r, tab.F_n[r], tab.F_t[r]});
}

// W plus the cell's work (without the factor dt/2) of the noted rows, after the pass: the rows in contact or loaded
// whose disc 1 is owned (index below n_owned), with this step's forces now in `tab`; a row that opened this step
// books the last half of its trapezoid. The discs' positions, velocities, spins and radii as the pass read them.
template <class Image>
double crossings_work(double W, const Image& image, const Vec2* x, const Vec2* v, const double* w, const double* R,
                      std::size_t n_owned, const ContactTable& tab, const Crossings& crossings) {
  for (const Crossing& c : crossings) {
    const auto i = static_cast<std::size_t>(tab.i1[c.r]);
    const auto j = static_cast<std::size_t>(tab.i2[c.r]);
    if (i >= n_owned) continue;  // booked by the rank that owns disc 1
    Vec2 dv;
    const Vec2 d = image.separation(x[i], x[j], dv);
    const double dist2 = dot(d, d);
    const double Rs = R[i] + R[j];
    const bool loaded = c.F_n != 0.0 || c.F_t != 0.0;
    if ((dist2 >= Rs * Rs && !loaded) || dist2 == 0.0 || (dv.x == 0.0 && dv.y == 0.0)) continue;  // as the pass
    const ContactKinematics k = disc_disc_kinematics(d, std::sqrt(dist2), R[i], R[j], v[i], v[j] + dv, w[i], w[j]);
    if (k.u_n <= 0.0)  // it opened this step: its forces are now zero
      W += c.F_t * dot(dv, k.t) - c.F_n * dot(dv, k.n);
    else
      W += (c.F_t + tab.F_t[c.r]) * dot(dv, k.t) - (c.F_n + tab.F_n[c.r]) * dot(dv, k.n);
  }
  return W;
}

}  // namespace rondel
