#pragma once
// The disc rolling on a flat wall of docs/validation.md sections 2 and 6: its set-up, the laws' equal-cap parameters,
// a run with its trace, and the formulas (test_rolling_wall.cpp, test_rolling_wall_ledger.cpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "support/Format.hpp"
#include "support/StandardObjects.hpp"
#include "support/TempDir.hpp"

namespace rondel::test::rolling_wall {

namespace fs = std::filesystem;

// D5 and contact set S.
constexpr double kR = test::d5::R;
constexpr double kDensity = test::d5::density;
constexpr double kG = test::d5::g;
constexpr double kKn = test::kSetS.k_n;
constexpr double kKs = test::kSetS.k_s;
constexpr double kMu = test::kSetS.mu;
constexpr double kDt = 1e-4;
constexpr double kDuration = 2.0;
constexpr double kV0 = 1.0;

using test::num;

// The disc and its static contact with the wall (docs/validation.md section 0).
struct DiscOnWall {
  double m, I, mg, u_n0, a;
  explicit DiscOnWall(double k_n = kKn) {
    m = test::d5::mass();
    I = 0.5 * m * kR * kR;
    mg = m * kG;
    u_n0 = mg / k_n;
    a = kR - 0.5 * u_n0;
  }
  double omega0(double v0) const { return -v0 / a; }
  double KE0(double v0) const { return 0.5 * (m * v0 * v0 + I * omega0(v0) * omega0(v0)); }
  // Deceleration of rolling without slip under a resisting couple M.
  double deceleration(double M) const { return M * a / (I + m * a * a); }
  double rigid_plastic_stop(double M, double v0) const { return a * KE0(v0) / M; }
  double first_stop(double M, double K, double v0) const { return a * (KE0(v0) / M + M / (2 * K)); }
  double rest(double M, double K, double v0) const { return first_stop(M, K, v0) - a * M / K; }
};

// One rolling law with its equal-cap parameters, its cap M on this disc and its spring stiffness K
// (0 for the rigid-plastic laws), all computed from the parameters it is given.
struct Law {
  std::string name;
  std::vector<std::string> overrides;
  double M = 0.0;  // cap of the resisting couple [N m]
  double K = 0.0;  // rolling stiffness [N m/rad]; 0: rigid-plastic
  std::string damping = "none";
};

// Equal-cap parameter map (docs/validation.md section 0). `damped` adds a rolling dashpot to the spring laws.
inline Law equal_cap(const std::string& name, bool damped = false) {
  const DiscOnWall d;
  const double F_n = d.mg;
  Law law{name, {"--contact.rolling=" + name}};
  auto set = [&](const std::string& key, double v) { law.overrides.push_back("--" + key + "=" + num(v)); };
  if (name == "jiang_plastic" || name == "jiang_brittle") {
    const double delta = 0.3, B = delta * 2 * kR;  // r = 2R at a wall
    set("jiang.delta", delta);
    law.K = kKn * B * B / 12;
    law.M = F_n * B / 6;
    if (damped) set("linear.zeta", 0.5), law.damping = "linear.zeta = 0.5 (mu_m = c_n B^2/12)";
  } else if (name == "wang" || name == "alonso_marroquin") {  // the same [wang] block
    const double mu_r = 0.1, k_r = 3e4;
    set("wang.mu_r", mu_r);
    set("wang.k_r", k_r);
    law.M = kR * mu_r * F_n;  // R* = R at a wall
    law.K = kR * kR * k_r;
    if (damped) set("wang.c_r", 100.0), law.damping = "wang.c_r = 100 N s/m";
  } else if (name == "iwashita_oda") {
    const double K_r = 0.75, eta = 0.1 * kR;
    set("iwashita_oda.K_r", K_r);
    set("iwashita_oda.eta", eta);
    set("iwashita_oda.C_r", damped ? 2.5e-3 : 0.0);
    if (damped) law.damping = "iwashita_oda.C_r = 2.5e-3 N m s/rad";
    law.M = eta * F_n;
    law.K = K_r;
  } else if (name == "force_proportional") {
    const double mu_r = 0.1;
    set("force_proportional.mu_r", mu_r);
    law.M = mu_r * F_n * d.a;
  } else if (name == "constant_torque") {
    const double mu_r = 0.05;
    set("constant_torque.mu_r", mu_r);
    set("constant_torque.f_lim", 0.0);  // the limiter off (docs/validation.md section 2)
    law.M = mu_r * 2 * kR * F_n;        // R_eq = 2R at a wall
  } else if (name == "displacement_damping") {
    const double mu_r = 0.05, theta_rmax = 0.035;
    set("displacement_damping.mu_r", mu_r);
    set("displacement_damping.theta_rmax", theta_rmax);
    law.M = mu_r * 2 * kR * F_n;
    law.K = law.M / theta_rmax;
    // The viscous part acts only in the elastic regime (f = 0), so the capped rolling phase is unchanged.
    if (damped)
      set("displacement_damping.nu", 0.5), set("displacement_damping.f", 0.0),
          law.damping = "displacement_damping.nu = 0.5, f = 0";
  } else {
    ADD_FAILURE() << "unknown law " << name;
  }
  return law;
}

// A scratch directory for the scene file, removed when the test ends.
struct ScratchDir : test::TempDir {
  ScratchDir() : test::TempDir("rondel-test-rolling-wall") {}
};

// The single disc on the bottom wall, ready to step.
class WallRun {
 public:
  WallRun(const Law& law, double v0 = kV0, double dt = kDt) {
    const DiscOnWall d;
    const fs::path scene = scratch_.path() / "disc.csv";
    std::ofstream(scene) << "id,x,y,radius,vx,vy,omega\n"
                         << "0,0," << num(kR - d.u_n0) << "," << num(kR) << "," << num(v0) << ",0," << num(d.omega0(v0))
                         << "\n";
    const std::string ini = "[run]\ndt = " + num(dt) + "\nprogress = false\n" +
                            "[domain]\nxlo = -0.05\nxhi = 2.5\nylo = 0\nyhi = 0.05\n" + "[gravity]\ny = " + num(-kG) +
                            "\n" + "[material]\ndensity = " + num(kDensity) + "\n" + "[linear]\nk_n = " + num(kKn) +
                            "\n" + "[coulomb]\nk_s = " + num(kKs) + "\nmu = " + num(kMu) + "\n" +
                            "[walls]\nbox = bottom\n" + "[scene]\ntype = csv\nfile = " + scene.string() + "\n";
    sim_ = std::make_unique<Simulation>(parse_config_text(ini, law.overrides), comm_, false);
    x0_ = sim_->discs().position[0].x;
  }
  Simulation& sim() { return *sim_; }
  double x() const { return sim_->discs().position[0].x - x0_; }  // displacement from the start
  double vx() const { return sim_->discs().velocity[0].x; }
  // The wall contact's history slot `name` (the row carrying a normal force).
  double slot(const std::string& name) const {
    const ContactTable& rows = sim_->wall_rows();
    const auto& names = rows.slot_names();
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) return NAN;
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (rows.F_n[r] > 0.0) return rows.slot[static_cast<std::size_t>(it - names.begin())][r];
    return NAN;
  }
  double absolute_residual() const { return sim_->ledger().absolute_residual(sim_->kinetic_energy()); }

 private:
  ScratchDir scratch_;
  Communicator comm_;
  std::unique_ptr<Simulation> sim_;
  double x0_ = 0.0;
};

// Tangential mode of the disc on its wall, sqrt(k_s (1/m + a^2/I)): the sudden couple at the start excites
// it (undamped in set S), so vx carries a ripple of amplitude decel/w_t and the first zero of vx may come
// up to 1/w_t early.
inline double tangential_frequency() {
  const DiscOnWall d;
  return std::sqrt(kKs * (1 / d.m + d.a * d.a / d.I));
}

// What a whole run shows, sampled every step.
struct Trace {
  std::vector<double> t, x, vx;
  std::size_t first_zero = 0;  // first sample with vx <= 0 (0: none)
  double residual_max = 0.0;   // largest ledger residual |KE - KE0 - W| over the largest KE so far

  double x_end() const { return x.back(); }
  // The first stop: the largest displacement up to the first zero of vx (the whole run if none).
  std::size_t first_stop() const {
    const auto last = first_zero > 0 ? x.begin() + static_cast<std::ptrdiff_t>(first_zero) + 1 : x.end();
    return static_cast<std::size_t>(std::max_element(x.begin(), last) - x.begin());
  }
  double first_stop_x() const { return x[first_stop()]; }
  double min_from(std::size_t i) const {
    return *std::min_element(x.begin() + static_cast<std::ptrdiff_t>(i), x.end());
  }
  double max_from(std::size_t i) const {
    return *std::max_element(x.begin() + static_cast<std::ptrdiff_t>(i), x.end());
  }
  double max_all() const { return max_from(0); }
  double mean_from(std::size_t i) const {
    double s = 0;
    for (std::size_t k = i; k < x.size(); ++k) s += x[k];
    return s / static_cast<double>(x.size() - i);
  }
  // First time x comes within tol of `target` (the run's length if never).
  double time_within(double target, double tol) const {
    for (std::size_t k = 0; k < x.size(); ++k)
      if (std::fabs(x[k] - target) <= tol) return t[k];
    return t.back();
  }
  // Last time |x - x_end| exceeded tol.
  double settle_time(double tol) const {
    for (std::size_t k = x.size(); k-- > 0;)
      if (std::fabs(x[k] - x_end()) > tol) return t[k];
    return 0.0;
  }
};

// Runs `duration` seconds; `hook(k)` is called after each sample k (0 = the initial state).
template <class Hook>
inline Trace run_trace(WallRun& run, double duration, Hook hook) {
  Simulation& sim = run.sim();
  Trace tr;
  const auto steps = static_cast<std::size_t>(std::llround(duration / sim.dt()));
  double scale = sim.kinetic_energy();
  tr.t.reserve(steps + 1), tr.x.reserve(steps + 1), tr.vx.reserve(steps + 1);
  for (std::size_t k = 0; k <= steps; ++k) {
    if (k > 0) sim.step();
    tr.t.push_back(sim.time());
    tr.x.push_back(run.x());
    tr.vx.push_back(run.vx());
    if (tr.first_zero == 0 && run.vx() <= 0.0) tr.first_zero = k;
    const double ke = sim.kinetic_energy();
    scale = std::max(scale, ke);
    tr.residual_max = std::max(tr.residual_max, sim.ledger().absolute_residual(ke) / scale);
    hook(k);
  }
  return tr;
}
inline Trace run_trace(WallRun& run, double duration = kDuration) {
  return run_trace(run, duration, [](std::size_t) {});
}

// Least-squares slope of vx over [t0, t1], negated.
inline double fitted_deceleration(const Trace& tr, double t0, double t1) {
  double n = 0, st = 0, sv = 0, stt = 0, stv = 0;
  for (std::size_t k = 0; k < tr.t.size(); ++k) {
    if (tr.t[k] < t0 || tr.t[k] > t1) continue;
    n += 1, st += tr.t[k], sv += tr.vx[k], stt += tr.t[k] * tr.t[k], stv += tr.t[k] * tr.vx[k];
  }
  return -(n * stv - st * sv) / (n * stt - st * st);
}

inline void print(const std::string& what, double got, double expected) {
  std::printf("    %-46s got %.10f expected %.10f (diff %+.3e)\n", what.c_str(), got, expected, got - expected);
}
inline void print_residual(const Trace& tr) {
  std::printf("    %-46s %.3e\n", "ledger residual, largest (relative)", tr.residual_max);
}

// E_total of docs/validation.md section 6, from the ledger and the diagnostics row:
//   E_total = KE + E_stored + D_slip + D_r_plastic + D_r_dashpot + E_r_break - W_g - W_w
// (kinetic energy, energy held by the normal, tangential and rolling springs now, the dissipation booked
// by mechanism, minus the work of gravity and of the walls). D_other (normal and tangential dashpots plus
// the integration error) is left out: the runs that use E_total have no normal or tangential dashpot, so
// E_total - E0 is the integration error of the split.
inline double energy_total(const DiagnosticsRow& r) {
  return r.ke_trans + r.ke_rot + r.E_stored + r.D_slip + r.D_r_plastic + r.D_r_dashpot + r.E_r_break - r.W_g - r.W_w;
}

}  // namespace rondel::test::rolling_wall
