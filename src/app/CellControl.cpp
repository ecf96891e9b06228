#include "app/CellControl.hpp"

#include <algorithm>

#include "app/RowGeometry.hpp"

namespace rondel {

CellStressSums CellControl::local_sums(const DiscStore& discs, const Domain& domain, const ContactTable& pairs) {
  CellStressSums out;
  const std::size_t n_owned = discs.n_owned();
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    if (static_cast<std::size_t>(pairs.i1[r]) >= n_owned || !(pairs.F_n[r] > 0.0)) continue;
    const Vec2 d = domain.separation(discs.position[pairs.i1[r]], discs.position[pairs.i2[r]]);
    const Vec2 f = RowGeometry::pair_force(discs, domain, pairs, r);
    out.sums[0] += d.x * f.x;
    out.sums[1] += d.y * f.y;
  }
  return out;
}

void CellControl::apply(Domain& cell, const FusedReduction& r, const std::array<std::size_t, 2>& slots) const {
  const double scale = -1.0 / (cell.length_x() * cell.length_y() * thickness_);
  double* const rate[2] = {&cell.L.xx, &cell.L.yy};
  for (std::size_t k = 0; k < 2; ++k) {
    if (!(target_[k] > 0.0)) continue;
    const double stress = scale * r.sum_exact(slots[k]).value();
    *rate[k] = std::clamp(gain_ * (stress - target_[k]) / target_[k], -max_rate_, max_rate_);
  }
  cell.rates();
}

}  // namespace rondel
