#pragma once
// Energy ledger (docs/physics.md section 5): the work of gravity W_g, of moving walls on discs W_w, and of the
// contact forces and couples W_c = W_n + W_t + W_r (+ W_b, the bonds') on the relative motion (negative when they
// resist), integrated with the half-step velocities, and D_damping, the work the integrator's local damping takes from
// the discs (run.local_damping), and W_cell, the work of a deforming periodic cell on the discs through the pairs
// across its boundary. Residual |KE - KE0 - W_g - W_w - W_cell - W_c + D_damping| relative to the largest of
// KE, |W_g|, |W_w| and |W_cell| so far is the run's reported integration error.
#include <algorithm>
#include <cmath>

#include "core/LedgerTerms.hpp"
#include "physics/ContactPass.hpp"

namespace rondel {

// The ledger's terms (core/LedgerTerms.hpp) with their integration.
struct EnergyLedger : LedgerTerms {
  void start(double KE) {
    KE0 = KE;
    scale = KE;
  }
  // Adds a step: the terms the kernel books, the work of gravity, and the local damping's loss in the step's
  // two kicks (0 when the damping is off).
  void add(const LedgerStep& s, double W_gravity, double damping = 0.0) {
    W_g += W_gravity;
    add_terms(s, kTermKernel);
    D_damping += damping;
  }
  double W_c() const { return W_n + W_t + W_r + W_b; }
  // What the dissipations by mechanism leave of -W_c once the springs' energy E_stored is counted: the
  // dashpots of the normal and tangential springs, and the integration error. The local damping is not a
  // part of -W_c (it acts on the discs' motion, not through the contacts).
  double D_other(double E_stored) const {
    double other = -W_c() - E_stored;
    for_each_term([&other](const LedgerTermInfo& t, double value) {
      if ((t.uses & kTermDissipation) && !(t.uses & kTermOfMotion)) other -= value;
    });
    return other;
  }
  // D_damping last: with the damping off it adds +0, which leaves every bit of the difference as it was.
  // W_cell after W_w, W_driver after it: in a standing box and without a script they subtract +0, which changes no
  // bit.
  double absolute_residual(double KE) const {
    return std::fabs(KE - KE0 - W_g - W_w - W_cell - W_driver - W_c() + D_damping);
  }
  // Updates the energy scale with the present state and returns the relative residual.
  double relative_residual(double KE) {
    scale = std::max({scale, KE, std::fabs(W_g), std::fabs(W_w), std::fabs(W_cell), std::fabs(W_driver)});
    return scale > 0.0 ? absolute_residual(KE) / scale : 0.0;
  }
};

}  // namespace rondel
