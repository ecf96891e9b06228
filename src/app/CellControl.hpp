#pragma once
// The stress control of a deforming periodic cell (docs/physics.md section 10): a diagonal component of the
// velocity gradient given as a target stress (cell.stress_xx, cell.stress_yy, compression positive) instead of a
// rate is steered every step by a servo on the cell's Love-Weber contact stress,
//   L_ii = clamp(g (S_ii - target_ii) / target_ii, -r_max, r_max),
// g = cell.servo_gain [1/s], r_max = cell.servo_max_rate [1/s]: the cell grows while it is over its target and
// shrinks below it. The stress sums are exact (ExactSum) and ride in the step's one reduction, as the controlled
// walls' loads do: the same rates on every rank count. The contact stress comes from the rows' forces and the
// positions after the kernel, which a checkpoint holds, so a restart steers with the same sums.
#include <array>
#include <cstddef>

#include "core/Config.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ExactSum.hpp"
#include "parallel/FusedReduction.hpp"

namespace rondel {

// This rank's share of sum d (x) f over the pairs it books, xx and yy.
struct CellStressSums {
  std::array<ExactSum, 2> sums;
  std::array<std::size_t, 2> add_to(FusedReduction& r) const { return {r.sum(sums[0]), r.sum(sums[1])}; }
};

class CellControl {
 public:
  CellControl() = default;
  explicit CellControl(const Config& c)
      : target_{c.cell_stress_xx, c.cell_stress_yy},
        gain_(c.cell_servo_gain),
        max_rate_(c.cell_servo_max_rate),
        thickness_(c.thickness) {}

  // The target of a component (0 xx, 1 yy; 0: rate-controlled) and a script's new one for a stress-controlled one.
  double target(int k) const { return target_[static_cast<std::size_t>(k)]; }
  void set_target(int k, double stress) { target_[static_cast<std::size_t>(k)] = stress; }
  // Whether any component is stress-controlled (then the step reduces every step).
  bool active() const { return target_[0] > 0.0 || target_[1] > 0.0; }
  static CellStressSums local_sums(const DiscStore& discs, const Domain& domain, const ContactTable& pairs);
  // The reduced sums into the controlled rates of `cell` (its rates() recomputed).
  void apply(Domain& cell, const FusedReduction& r, const std::array<std::size_t, 2>& slots) const;

 private:
  std::array<double, 2> target_{0.0, 0.0};
  double gain_ = 0.0, max_rate_ = 0.0, thickness_ = 1.0;
};

}  // namespace rondel
