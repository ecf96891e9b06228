#pragma once
// Energy ledger (docs/physics.md section 5): the work of gravity W_g, of moving walls on discs W_w, and of the
// contact forces and couples W_c = W_n + W_t + W_r on the relative motion (negative when they resist),
// integrated with the half-step velocities. Residual |KE - KE0 - W_g - W_w - W_c| relative to the largest
// of KE, |W_g| and |W_w| so far is the run's reported integration error.
#include <algorithm>
#include <cmath>

#include "core/LedgerTerms.hpp"
#include "physics/ContactKernel.hpp"

namespace rondel {

// The ledger's terms (core/LedgerTerms.hpp) with their integration.
struct EnergyLedger : LedgerTerms {
  void start(double KE) {
    KE0 = KE;
    scale = KE;
  }
  // Adds a step: the terms the kernel books, and the work of gravity.
  void add(const LedgerStep& s, double W_gravity) {
    W_g += W_gravity;
    add_terms(s, kTermKernel);
  }
  double W_c() const { return W_n + W_t + W_r; }
  // What the dissipations by mechanism leave of -W_c once the springs' energy E_stored is counted: the
  // dashpots of the normal and tangential springs, and the integration error.
  double D_other(double E_stored) const {
    double other = -W_c() - E_stored;
    for_each_term([&other](const LedgerTermInfo& t, double value) {
      if (t.uses & kTermDissipation) other -= value;
    });
    return other;
  }
  double absolute_residual(double KE) const { return std::fabs(KE - KE0 - W_g - W_w - W_c()); }
  // Updates the energy scale with the present state and returns the relative residual.
  double relative_residual(double KE) {
    scale = std::max({scale, KE, std::fabs(W_g), std::fabs(W_w)});
    return scale > 0.0 ? absolute_residual(KE) / scale : 0.0;
  }
};

}  // namespace rondel
