#pragma once
// The parallel bond of Potyondy & Cundall (2004) in 2D (docs/physics.md section 12): an elastic beam of rectangular
// section between two discs that acts beside their contact law and breaks in tension or shear. This file is the
// law: its [bonds] block, its geometry, one step of its forces, its breaking test, its stored energy and the strengths
// drawn per bond. The rows that carry bonds and their pass after the contact kernel: physics/BondPass.hpp.
//
//   geometry: Rb = lambda min(R1, R2),  A = 2 Rb t,  I = (2 Rb)^3 t/12,  t the discs' thickness
//   update (half-step velocities, canonical frame of the kinematics: v_n = (v2 - v1).n, V_s, w1 - w2):
//     Fb_n += kb_n A v_n dt        (tension > 0: separating discs load it)
//     Fb_s += -kb_s A V_s dt       (a tangential force on disc 1 along t, as the coulomb spring's -k_s xi)
//     Mb   += -kb_n I (w1 - w2) dt (a couple on disc 1; -Mb on disc 2)
//   on disc 1: +Fb_n n + Fb_s t and the couple Mb (the contact law's terms beside them)
//   breaking: sigma = Fb_n/A + |Mb| Rb/I >= sigma_c (tension) or tau = |Fb_s|/A >= tau_c (shear); both in one step:
//     the mode whose stress is the larger fraction of its strength
//   stored energy: Fb_n^2/(2 kb_n A) + Fb_s^2/(2 kb_s A) + Mb^2/(2 kb_n I), released when it breaks
// Everything is a function of the kinematics' objective rates (v_n, V_s, w1 - w2), so a rigid motion of the pair
// changes no force.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"

namespace rondel {

// [bonds] and its pair blocks [bonds.A.B]: a bond's parameters per pair of materials (ContactParams' bond fields).
// Each bond's strength is uniform in mean (1 +- spread), spread in [0, 1).
inline constexpr Range kSpread{0.0, 1.0, false, true};
inline constexpr ParamSpec kBondParams[] = {
    {"kb_n", "Pa/m", Presence::required, 0.0, kPositive, "bond normal stiffness per area", &ContactParams::kb_n, 1e9},
    {"kb_s", "Pa/m", Presence::required, 0.0, kPositive, "bond shear stiffness per area", &ContactParams::kb_s, 0.5e9},
    {"sigma_c", "Pa", Presence::required, 0.0, kPositive, "mean tensile strength", &ContactParams::sigma_c, 1e4},
    {"tau_c", "Pa", Presence::required, 0.0, kPositive, "mean shear strength", &ContactParams::tau_c, 1e4},
    {"sigma_spread", "-", Presence::defaulted, 0.0, kSpread, "relative spread of the tensile strength per bond",
     &ContactParams::sigma_spread},
    {"tau_spread", "-", Presence::defaulted, 0.0, kSpread, "relative spread of the shear strength per bond",
     &ContactParams::tau_spread},
    {"lambda", "-", Presence::defaulted, 1.0, kPositive, "bond radius Rb = lambda min(R1, R2)",
     &ContactParams::bond_lambda},
};
inline constexpr LawBlock kBondBlock{"bonds", "parallel bonds (Potyondy & Cundall 2004; any key turns bonds on)",
                                     kBondParams};

// The beam's section: radius Rb [m], area A [m^2 per thickness t], second moment I [m^4].
struct BondGeometry {
  double Rb = 0.0, A = 0.0, I = 0.0;
  static BondGeometry of(double R1, double R2, double thickness, double lambda) {
    const double Rb = lambda * std::min(R1, R2);
    const double h = 2.0 * Rb;
    return {Rb, h * thickness, h * h * h * thickness / 12.0};
  }
};

enum class BondMode : int { intact = 0, tension = 1, shear = 2 };

// A bond's state (its history columns): normal force (tension positive), shear force and moment.
struct BondState {
  double Fb_n = 0.0, Fb_s = 0.0, Mb = 0.0;
};

// One step of a bond: its state after the step, the stresses it carried, and how it broke (intact: it did not).
struct BondStep {
  BondState state;
  double sigma = 0.0, tau = 0.0;  // [Pa]
  BondMode mode = BondMode::intact;
};

inline double bond_stored(const ContactParams& p, const BondGeometry& g, const BondState& s) {
  return s.Fb_n * s.Fb_n / (2.0 * p.kb_n * g.A) + s.Fb_s * s.Fb_s / (2.0 * p.kb_s * g.A) +
         s.Mb * s.Mb / (2.0 * p.kb_n * g.I);
}

// The stresses of the breaking test: sigma = Fb_n/A + |Mb| Rb/I (tension), tau = |Fb_s|/A (shear) [Pa].
struct BondStresses {
  double sigma, tau;
  static BondStresses of(const BondGeometry& g, const BondState& s) {
    return {s.Fb_n / g.A + std::fabs(s.Mb) * g.Rb / g.I, std::fabs(s.Fb_s) / g.A};
  }
};

// The step: the increments from the kinematics' rates, then the breaking test against this bond's strengths.
inline BondStep bond_step(const ContactParams& p, const BondGeometry& g, const ContactKinematics& k, double dt,
                          const BondState& before, double sigma_c, double tau_c) {
  BondStep out;
  BondState& s = out.state;
  s.Fb_n = before.Fb_n + p.kb_n * g.A * k.v_n * dt;
  s.Fb_s = before.Fb_s - p.kb_s * g.A * k.V_s * dt;
  s.Mb = before.Mb - p.kb_n * g.I * k.thetadot_r * dt;
  const BondStresses stress = BondStresses::of(g, s);
  out.sigma = stress.sigma, out.tau = stress.tau;
  const double r_t = out.sigma / sigma_c, r_s = out.tau / tau_c;
  if (r_t >= 1.0 || r_s >= 1.0) out.mode = r_t >= r_s ? BondMode::tension : BondMode::shear;
  return out;
}

// A number in [0, 1) from a bond's pair of gids and a salt (one per drawn quantity): splitmix64 of the three, so
// that a bond's strengths are the same on any rank count, in any order of creation and after a restart.
inline double bond_uniform(std::int64_t lo, std::int64_t hi, std::uint64_t salt) {
  auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  const std::uint64_t z = mix(mix(mix(static_cast<std::uint64_t>(lo)) ^ static_cast<std::uint64_t>(hi)) ^ salt);
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

// The strength of the bond (lo, hi): mean (1 + spread (2u - 1)), u = bond_uniform(lo, hi, salt).
inline double bond_strength(double mean, double spread, std::int64_t lo, std::int64_t hi, std::uint64_t salt) {
  return spread == 0.0 ? mean : mean * (1.0 + spread * (2.0 * bond_uniform(lo, hi, salt) - 1.0));
}
inline constexpr std::uint64_t kTensileSalt = 0x7465'6e73'696c'6531ULL;  // "tensile1"
inline constexpr std::uint64_t kShearSalt = 0x7368'6561'7273'7431ULL;    // "shearst1"

// The strengths of the bond (lo, hi) with the pair's parameters.
struct BondStrengths {
  double sigma_c, tau_c;
  static BondStrengths of(const ContactParams& p, std::int64_t lo, std::int64_t hi) {
    return {bond_strength(p.sigma_c, p.sigma_spread, lo, hi, kTensileSalt),
            bond_strength(p.tau_c, p.tau_spread, lo, hi, kShearSalt)};
  }
};

}  // namespace rondel
