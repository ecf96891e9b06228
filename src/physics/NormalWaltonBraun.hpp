#pragma once
// Walton-Braun hysteretic normal law (Walton & Braun 1986; docs/physics.md section 11), without tension:
//   loading line (u_n >= u_max):  F_n = K1 u_n,  and u_max = u_n
//   otherwise (unloading, reloading): F_n = max(0, K2 (u_n - u_0)),  u_0 = u_max (1 - K1/K2)
// K1 the loading stiffness (k_n), K2 = K1/e^2 the unloading one (given, or from the pair's e at set-up:
// PairConstants.cpp). The history is the contact's largest overlap u_max, kept while the discs overlap (even at
// F_n = 0) and forgotten when they part. A head-on impact rebounds with e = sqrt(K1/K2) at any speed.
// Energy: the stored energy is what unloading along K2 gives back, F_n^2/(2 K2); the rest of the work is
// dissipated, K1 (1 - K1/K2) (u_max'^2 - u_max^2)/2 when the loading line moves from u_max to u_max' (the
// ledger's D_n_hyst). The tangential and rolling laws see K1 (jiang_*: K_m = K1 B^2/12) and no dashpot; the
// critical step's normal mode and the servo see K2 (stiffest()).
#include <array>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

// [walton_braun]: one of e and K2 (the block's one_of, required).
inline constexpr ParamSpec kWaltonBraunParams[] = {
    {"K1", "N/m", Presence::required, 0.0, kPositive, "loading stiffness", &ContactParams::k_n, 1e6},
    {"e", "-", Presence::optional, -1.0, kRestitution, "restitution coefficient of the pair (K2 = K1/e^2)",
     &ContactParams::e_wb, 0.5},
    {"K2", "N/m", Presence::optional, -1.0, kPositive, "unloading stiffness, at least K1 (instead of e)",
     &ContactParams::k_unload},
};
inline constexpr const char* kWaltonBraunUnloading[] = {"e", "K2"};
inline constexpr LawBlock kWaltonBraunBlock{"walton_braun",
                                            "hysteretic normal law: loading K1, unloading K2, no tension",
                                            kWaltonBraunParams, kWaltonBraunUnloading, true};

struct NormalWaltonBraun {
  static constexpr const char* name = "walton_braun";
  static constexpr const LawBlock* block = &kWaltonBraunBlock;
  static constexpr bool kStiffening = false;
  static constexpr bool kHysteresis = true;
  static constexpr std::array<const char*, 1> slots{"u_max"};
  struct History {
    double& u_max;  // the largest overlap of the contact so far [m]
  };

  static NormalForce force(const ContactInput& in, History h) {
    const double u = in.k.u_n, K1 = in.p.k_n, K2 = in.p.k_unload;
    if (u >= h.u_max) {
      const double loss = 0.5 * K1 * (1.0 - K1 / K2) * (u * u - h.u_max * h.u_max);
      h.u_max = u;
      return {K1 * u, loss};
    }
    const double f = K2 * (u - h.u_max * (1.0 - K1 / K2));
    return {f > 0.0 ? f : 0.0};
  }
  // What unloading along K2 gives back: F_n^2/(2 K2), the force at this overlap with the history as it is.
  static double stored(const ContactInput& in, History h) {
    double u_max = h.u_max;
    const double F = force(in, History{u_max}).F_n;
    return F * F / (2.0 * in.p.k_unload);
  }
  // The tangential and rolling laws see the loading stiffness K1 and no dashpot.
  static ContactParams linearised(const ContactInput& in) { return without_dashpot(in.p); }
  // The critical step's normal mode and the servo: the unloading stiffness K2.
  static ContactParams stiffest(const ContactInput& in) {
    ContactParams q = without_dashpot(in.p);
    q.k_n = in.p.k_unload;
    return q;
  }

 private:
  static ContactParams without_dashpot(ContactParams q) {
    q.c_n_fixed = 0.0;
    return q;
  }
};

}  // namespace rondel
