#pragma once
// Test support: the standard objects of docs/validation.md section 0, written once: disc D5, contact sets S and
// J, and the equal-cap parameter map of the rolling laws (every law's cap 0.1 F_n R at a wall).
#include <cmath>
#include <numbers>
#include <ostream>

#include "core/ContactParams.hpp"

namespace rondel::test {

// Disc D5: R = 5 mm, rho = 2650 kg/m^3, thickness 1 m, under g = 9.81 m/s^2.
namespace d5 {
constexpr double R = 0.005, density = 2650.0, thickness = 1.0, g = 9.81;
inline double mass() { return density * std::numbers::pi * R * R; }  // thickness 1 m
inline double inertia() { return 0.5 * mass() * R * R; }
}  // namespace d5

// Contact sets S (soft) and J (stiff), both with mu = 0.5.
struct ContactSet {
  const char* name;
  double k_n, k_s, mu;
};
inline void PrintTo(const ContactSet& s, std::ostream* os) { *os << "set " << s.name; }
inline constexpr ContactSet kSetS{"S", 1e6, 0.75e6, 0.5};
inline constexpr ContactSet kSetJ{"J", 2e8, 1.5e8, 0.5};

inline ContactParams params_of(const ContactSet& set) {
  ContactParams p;
  p.k_n = set.k_n;
  p.k_s = set.k_s;
  p.mu = set.mu;
  return p;
}
inline ContactParams set_S() { return params_of(kSetS); }
inline ContactParams set_J() { return params_of(kSetJ); }

// The equal-cap parameter map (docs/validation.md section 0).
namespace equal_cap {
constexpr double jiang_delta = 0.3;
constexpr double wang_mu_r = 0.1, wang_k_r = 3e4;
constexpr double io_K_r = 0.75, io_eta = 5e-4;
constexpr double ct_mu_r = 0.05;
constexpr double dd_mu_r = 0.05, dd_theta_rmax = 0.035;
constexpr double fp_mu_r = 0.1;
}  // namespace equal_cap

}  // namespace rondel::test
