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
