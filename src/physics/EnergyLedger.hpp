#pragma once
// Energy ledger (PHYSICS.md section 5): the work of gravity W_g, of moving walls on discs W_w, and of the
// contact forces and couples W_c = W_n + W_t + W_r on the relative motion (negative when they resist),
// integrated with the half-step velocities. Residual |KE - KE0 - W_g - W_w - W_c| relative to the largest
// of KE, |W_g| and |W_w| so far is the run's reported integration error.
#include <algorithm>
#include <cmath>

#include "physics/ContactKernel.hpp"

namespace rondel {

struct EnergyLedger {
  double KE0 = 0.0;
  double W_g = 0.0, W_w = 0.0, W_n = 0.0, W_t = 0.0, W_r = 0.0;
  // Dissipation by mechanism (>= 0): Coulomb slip, rolling plastic work, rolling dashpots, and the stored
  // rolling energy released when brittle contacts break. -W_c = stored + these + the rest (dashpots of
  // the normal and tangential springs, and the integration error).
  double D_slip = 0.0, D_r_plastic = 0.0, D_r_dashpot = 0.0, E_r_break = 0.0;
  double scale = 0.0;  // largest of KE, |W_g|, |W_w| seen at the diagnostics so far

  void start(double KE) {
    KE0 = KE;
    scale = KE;
  }
  void add(const LedgerStep& s, double W_gravity) {
    W_g += W_gravity;
    W_w += s.W_w;
    W_n += s.W_n;
    W_t += s.W_t;
    W_r += s.W_r;
    D_slip += s.D_slip;
    D_r_plastic += s.D_r_plastic;
    D_r_dashpot += s.D_r_dashpot;
    E_r_break += s.E_r_break;
  }
  double W_c() const { return W_n + W_t + W_r; }
  double absolute_residual(double KE) const { return std::fabs(KE - KE0 - W_g - W_w - W_c()); }
  // Updates the energy scale with the present state and returns the relative residual.
  double relative_residual(double KE) {
    scale = std::max({scale, KE, std::fabs(W_g), std::fabs(W_w)});
    return scale > 0.0 ? absolute_residual(KE) / scale : 0.0;
  }
};

}  // namespace rondel
