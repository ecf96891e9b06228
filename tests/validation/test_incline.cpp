// A disc on an inclined wall, docs/validation.md section 3: disc D5 and contact set S of section 0, every
// rolling law in the equal-cap parameter map (wall cap M_max = 0.1 F_n R; force_proportional 0.1 F_n a).
//
// The incline is the flat bottom wall (a line at y = 0, normal +y) with gravity turned by beta:
// g = (g sin(beta), -g cos(beta)), so "downhill" is +x. At the wall contact n = (0, -1) and t = (1, 0); a
// disc rolling downhill spins clockwise (omega < 0) and the resisting couple is M > 0. Each run starts the
// disc at rest at the static overlap u_n0 = m g cos(beta)/k_n, so F_n = m g cos(beta) throughout
// (the disc only moves along the wall, v_n = 0) and the lever is a = R - u_n0/2.
//
// The expected values are computed here from the formulas of docs/validation.md section 3:
//  - static hold (spring K in series with k_s): x = m g sin(beta) (1/k_s + a^2/K), |theta| = m g a sin(beta)/K;
//  - critical angle: m g a sin(beta) = M_max(F_n = m g cos(beta)), solved for beta by bisection;
//  - above it, rolling without slip: dv/dt = (m g a^2 sin(beta) - M_max a)/(I + m a^2);
//  - below it the rigid-plastic laws (constant_torque, force_proportional) creep at a speed proportional to
//    dt, while an elastic-plastic law holds.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "support/Format.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;
// Disc D5 and contact set S (docs/validation.md section 0).
constexpr double kR = test::d5::R, kRho = test::d5::density, kThick = test::d5::thickness, kG = test::d5::g;
constexpr double kKn = test::kSetS.k_n, kKs = test::kSetS.k_s, kMu = test::kSetS.mu;
const double kMass = kRho * kPi * kR * kR * kThick;
const double kInertia = 0.5 * kMass * kR * kR;
const double kWeight = kMass * kG;

// ---------------------------------------------------------------------------------------------------------
// The laws in the equal-cap parameter map, with their cap and rolling stiffness computed from the parameters.
struct LawSetup {
  std::string name;
  std::vector<std::string> overrides;
  // Wall cap M_max [N m] at normal force F_n and lever a.
  std::function<double(double F_n, double a)> cap;
  // Rolling spring stiffness K [N m/rad] at normal force F_n (0: no spring).
  std::function<double(double F_n)> stiffness;
};

// Equal-cap map parameters (docs/validation.md section 0).
constexpr double kJiangDelta = test::equal_cap::jiang_delta;
constexpr double kWangMuR = test::equal_cap::wang_mu_r, kWangKr = test::equal_cap::wang_k_r;
constexpr double kIoKr = test::equal_cap::io_K_r, kIoEta = test::equal_cap::io_eta;
constexpr double kCtMuR = test::equal_cap::ct_mu_r;
constexpr double kDdMuR = test::equal_cap::dd_mu_r, kDdThetaMax = test::equal_cap::dd_theta_rmax;
constexpr double kFpMuR = test::equal_cap::fp_mu_r;

using test::num;

// `damped`: add rolling damping so that an elastic-plastic law settles (about half the critical damping of
// the rolling mode, C ~ 2.4e-3 N m s against 2 sqrt(K (I + m a^2)) = 4.8e-3; displacement_damping
// overdamped and only in the elastic regime, f = 0, so that rolling above the critical angle meets the
// bare cap). The dashpots do no work at rest, so the static state and the cap are unchanged.
LawSetup jiang(const std::string& name, bool damped) {
  const double B = kJiangDelta * 2.0 * kR;  // r -> 2R at a wall
  LawSetup s{name,
             {"--jiang.delta=" + num(kJiangDelta)},
             [B](double F_n, double) { return F_n * B / 6.0; },
             [B](double) { return kKn * B * B / 12.0; }};
  // mu_m = c_n B^2/12 with c_n = 2 zeta sqrt(m k_n): zeta = 3.5 gives mu_m = 2.4e-3 N m s. The normal
  // dashpot itself does nothing here (v_n = 0).
  if (damped) s.overrides.push_back("--linear.zeta=3.5");
  return s;
}
LawSetup wang(bool damped) {
  LawSetup s{"wang",
             {"--wang.mu_r=" + num(kWangMuR), "--wang.k_r=" + num(kWangKr)},
             [](double F_n, double) { return kWangMuR * F_n * kR; },  // R* -> R at a wall
             [](double) { return kWangKr * kR * kR; }};
  if (damped) s.overrides.push_back("--wang.c_r=100");  // c_r R^2 = 2.5e-3 N m s
  return s;
}
// alonso_marroquin: wang's spring-slider and [wang] block on W15's model-2 rolling velocity (docs/physics.md
// section 3). Its rolling dashpot does not damp the undamped tangential spring of set S: near rest the spring's
// ripple gives s1 = R omega and s2 = -V_t different signs, and then the law has no couple change and no dashpot
// (docs/validation.md section 10). So `damped` damps the tangential spring too (coulomb.zeta_t = 0.5), which
// changes neither the static state nor rolling without slip.
LawSetup alonso_marroquin(bool damped) {
  LawSetup s = wang(damped);
  s.name = "alonso_marroquin";
  if (damped) s.overrides.push_back("--coulomb.zeta_t=0.5");
  return s;
}
LawSetup iwashita_oda(bool damped) {
  return {"iwashita_oda",
          {"--iwashita_oda.K_r=" + num(kIoKr), "--iwashita_oda.eta=" + num(kIoEta),
           std::string("--iwashita_oda.C_r=") + (damped ? "2.4e-3" : "0")},
          [](double F_n, double) { return kIoEta * F_n; },
          [](double) { return kIoKr; }};
}
LawSetup displacement_damping(bool damped) {
  LawSetup s{"displacement_damping",
             {"--displacement_damping.mu_r=" + num(kDdMuR), "--displacement_damping.theta_rmax=" + num(kDdThetaMax)},
             [](double F_n, double) { return kDdMuR * 2.0 * kR * F_n; },
             [](double F_n) { return kDdMuR * 2.0 * kR * F_n / kDdThetaMax; }};
  if (damped) {
    // nu = 1.5: the soft spring (k_r = 0.029 N m/rad, rolling mode 61 rad/s) overdamped, so that a sudden
    // load just below the cap does not overshoot it; f = 0: no viscous part at the limit.
    s.overrides.push_back("--displacement_damping.nu=1.5");
    s.overrides.push_back("--displacement_damping.f=0");
  }
  return s;
}
// f_lim = 0: the moment limiter off (docs/validation.md section 2), unless f_lim is given.
LawSetup constant_torque(double f_lim = 0.0) {
  return {"constant_torque",
          {"--constant_torque.mu_r=" + num(kCtMuR), "--constant_torque.f_lim=" + num(f_lim)},
          [](double F_n, double) { return kCtMuR * 2.0 * kR * F_n; },
          [](double) { return 0.0; }};
}
LawSetup force_proportional() {
  return {"force_proportional",
          {"--force_proportional.mu_r=" + num(kFpMuR)},
          [](double F_n, double a) { return kFpMuR * F_n * a; },
          [](double) { return 0.0; }};
}

// ---------------------------------------------------------------------------------------------------------
// Formulas of docs/validation.md section 3.
double normal_force(double beta) { return kWeight * std::cos(beta); }
double lever(double beta) { return kR - 0.5 * normal_force(beta) / kKn; }
// Driving moment of gravity about the contact point, m g a sin(beta).
double drive(double beta) { return kWeight * lever(beta) * std::sin(beta); }

double critical_angle(const LawSetup& law) {
  auto excess = [&](double beta) { return drive(beta) - law.cap(normal_force(beta), lever(beta)); };
  double lo = 1.0 * kDeg, hi = 20.0 * kDeg;
  EXPECT_LT(excess(lo), 0.0);
  EXPECT_GT(excess(hi), 0.0);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (excess(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

double rolling_acceleration(const LawSetup& law, double beta) {
  const double a = lever(beta);
  return (kWeight * a * a * std::sin(beta) - law.cap(normal_force(beta), a) * a) / (kInertia + kMass * a * a);
}

// ---------------------------------------------------------------------------------------------------------
// One run: the disc placed at rest at the static overlap on the incline of angle beta.
class InclineRun {
 public:
  InclineRun(const LawSetup& law, double beta, double dt) {
    static int counter = 0;
    const fs::path dir =
        fs::temp_directory_path() / ("rondel_incline_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::create_directories(dir);
    const fs::path csv = dir / "disc.csv";
    u_n0_ = normal_force(beta) / kKn;
    y0_ = kR - u_n0_;
    {
      std::ofstream out(csv);
      out << "# id,x,y,radius,vx,vy,omega\n0," << num(0.0) << "," << num(y0_) << "," << num(kR) << ",0,0,0\n";
    }
    const std::string ini = "[run]\nprogress = false\ndt = " + num(dt) +
                            "\n[domain]\nxlo = -0.5\nxhi = 1.5\nylo = 0\nyhi = 0.1\n"
                            "[gravity]\nx = " +
                            num(kG * std::sin(beta)) + "\ny = " + num(-kG * std::cos(beta)) +
                            "\n[material]\ndensity = " + num(kRho) + "\nthickness = " + num(kThick) +
                            "\n[contact]\nrolling = " + law.name + "\n[linear]\nk_n = " + num(kKn) +
                            "\n[coulomb]\nk_s = " + num(kKs) + "\nmu = " + num(kMu) +
                            "\n[walls]\nbox = bottom\n[scene]\ntype = csv\nfile = " + csv.string() + "\n";
    sim_ = std::make_unique<Simulation>(parse_config_text(ini, law.overrides), comm_, false);
    fs::remove_all(dir);
    EXPECT_DOUBLE_EQ(sim_->discs().mass[0], kMass);
    EXPECT_DOUBLE_EQ(sim_->discs().inertia[0], kInertia);
    EXPECT_DOUBLE_EQ(sim_->dt(), dt);
  }

  void step() { sim_->step(); }
  double t() const { return sim_->time(); }
  double x() const { return sim_->discs().position[0].x; }
  double y() const { return sim_->discs().position[0].y; }
  double v() const { return sim_->discs().velocity[0].x; }
  double theta() const { return sim_->discs().theta[0]; }
  double omega() const { return sim_->discs().omega[0]; }
  double y0() const { return y0_; }

 private:
  Communicator comm_;
  std::unique_ptr<Simulation> sim_;
  double u_n0_ = 0.0, y0_ = 0.0;
};

// Least-squares fit x(t) = c0 + c1 t + c2 t^2; returns the acceleration 2 c2.
struct QuadFit {
  double n = 0, st = 0, st2 = 0, st3 = 0, st4 = 0, sx = 0, stx = 0, st2x = 0;
  double t_ref = 0.0;
  void add(double t, double x) {
    t -= t_ref;
    n += 1;
    st += t, st2 += t * t, st3 += t * t * t, st4 += t * t * t * t;
    sx += x, stx += t * x, st2x += t * t * x;
  }
  double acceleration() const {
    // Normal equations, Cramer's rule for c2.
    auto det3 = [](double a, double b, double c, double d, double e, double f, double g, double h, double i) {
      return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
    };
    const double D = det3(n, st, st2, st, st2, st3, st2, st3, st4);
    const double D2 = det3(n, st, sx, st, st2, stx, st2, st3, st2x);
    return 2.0 * D2 / D;
  }
};

// A run of duration T: the state at the end, the least-squares acceleration over [fit_from, T] and the
// mean positions over two windows (for the mean creep speed).
struct Trace {
  double x = 0, v = 0, theta = 0, omega = 0;
  double acc = 0;
  double creep = 0;  // (mean x over window b - mean x over window a)/(mean t over b - mean t over a)
};
struct Windows {
  double a0, a1, b0, b1;
};

Trace run_for(const LawSetup& law, double beta, double dt, double T, double fit_from,
              Windows w = {0.2, 0.6, 0.6, 1.0}) {
  InclineRun run(law, beta, dt);
  const auto steps = std::lround(T / dt);
  QuadFit fit;
  fit.t_ref = 0.5 * (fit_from + T);
  double sa = 0, sb = 0, ta = 0, tb = 0;
  long na = 0, nb = 0;
  Trace out;
  for (long s = 0; s < steps; ++s) {
    run.step();
    const double t = run.t();
    if (t >= fit_from) fit.add(t, run.x());
    if (t > w.a0 && t <= w.a1) sa += run.x(), ta += t, ++na;
    if (t > w.b0 && t <= w.b1) sb += run.x(), tb += t, ++nb;
    // The disc stays on the wall: F_n = m g cos(beta) throughout (the centre never leaves y0).
    EXPECT_NEAR(run.y(), run.y0(), 1e-12 * kR) << law.name << " t = " << t;
  }
  out.x = run.x(), out.v = run.v(), out.theta = run.theta(), out.omega = run.omega();
  out.acc = fit.acceleration();
  if (na > 0 && nb > 0) out.creep = (sb / nb - sa / na) / (tb / nb - ta / na);
  return out;
}

// ---------------------------------------------------------------------------------------------------------
TEST(Incline, CriticalAngleFormula) {
  // The formula code checked once against docs/validation.md's numbers.
  const double jiang_c = critical_angle(jiang("jiang_plastic", false)) / kDeg;
  const double fp_c = critical_angle(force_proportional()) / kDeg;
  EXPECT_NEAR(jiang_c, 5.71175, 1e-5);
  EXPECT_NEAR(fp_c, 5.71059, 1e-5);
  for (const LawSetup& law : {wang(false), alonso_marroquin(false), iwashita_oda(false), constant_torque(),
                              displacement_damping(false), jiang("jiang_brittle", false)})
    EXPECT_NEAR(critical_angle(law) / kDeg, jiang_c, 1e-9) << law.name;
  // The lever and the static overlap of docs/validation.md section 0 (beta = 0).
  EXPECT_NEAR(kWeight, 2.0417603, 1e-7);
  EXPECT_NEAR(lever(0.0), 4.9989791e-3, 1e-10);
  std::printf("critical angle: cap 0.1 F_n R %.7f deg, cap 0.1 F_n a %.7f deg\n", jiang_c, fp_c);
}

// Static hold of the elastic-plastic laws (with rolling damping, so that they settle):
// x = m g sin(beta) (1/k_s + a^2/K) and theta = -m g a sin(beta)/K to 1e-4 relative. alonso_marroquin to 1e-2:
// its spring moves by V_r2 = the smaller of s1 = R omega and s2 = -V_t, so while the load comes on (the tangential
// spring stretching) x_r gains less than R theta, and the disc turns further before the spring holds it
// (measured 0.3 % at both angles).
TEST(Incline, StaticHoldBelowCriticalAngle) {
  const double dt = 5e-5;
  for (double beta_deg : {2.0, 4.0}) {
    const double beta = beta_deg * kDeg;
    for (const LawSetup& law : {jiang("jiang_plastic", true), jiang("jiang_brittle", true), wang(true),
                                alonso_marroquin(true), iwashita_oda(true), displacement_damping(true)}) {
      SCOPED_TRACE(law.name + " beta = " + num(beta_deg));
      // displacement_damping's spring is 26x softer (rolling mode 61 rad/s): it needs longer to settle.
      const double T = law.name == "displacement_damping" ? 1.5 : 0.4;
      const Trace r = run_for(law, beta, dt, T, 0.5 * T);
      const double a = lever(beta);
      const double K = law.stiffness(normal_force(beta));
      const double x_exp = kWeight * std::sin(beta) * (1.0 / kKs + a * a / K);
      const double th_exp = -drive(beta) / K;
      std::printf("hold %-22s beta %.1f: x = %.9e (exp %.9e, rel %+.1e)  theta = %.9e (exp %.9e, rel %+.1e)\n",
                  law.name.c_str(), beta_deg, r.x, x_exp, r.x / x_exp - 1, r.theta, th_exp, r.theta / th_exp - 1);
      const double tol = law.name == "alonso_marroquin" ? 1e-2 : 1e-4;
      EXPECT_NEAR(r.x, x_exp, tol * x_exp);
      EXPECT_NEAR(r.theta, th_exp, tol * std::fabs(th_exp));
      EXPECT_LT(std::fabs(r.v), 1e-6 * x_exp / T);  // at rest
    }
  }
}

// The critical angle, bracketed by runs at beta_c -+ 0.015 degrees (docs/validation.md tolerance 0.02 degrees),
// with beta_c from m g a sin(beta) = M_max(F_n = m g cos(beta)) for each law. Each run lasts 1.5 s (the
// sudden load just below the cap makes the elastic-plastic laws yield a little before they stop, within
// about 0.5 s); the acceleration is fitted over the last 0.5 s.
//  - below: no sustained acceleration (|dv/dt| < 2 % of the rolling acceleration just above); an
//    elastic-plastic law is at rest; a rigid-plastic law creeps at a constant speed (tested below);
//  - above: rolling with dv/dt = (m g a^2 sin(beta) - M_max a)/(I + m a^2) (1e-4 relative).
TEST(Incline, CriticalAngleBracket) {
  const double dt = 5e-5, T = 1.5, fit_from = 1.0, dbeta = 0.015 * kDeg;
  for (const LawSetup& law : {jiang("jiang_plastic", true), wang(true), alonso_marroquin(true), iwashita_oda(true),
                              displacement_damping(true), constant_torque(), force_proportional()}) {
    SCOPED_TRACE(law.name);
    const double beta_c = critical_angle(law);
    const bool rigid_plastic = law.name == "constant_torque" || law.name == "force_proportional";
    const double A_above = rolling_acceleration(law, beta_c + dbeta);
    ASSERT_GT(A_above, 0.0);
    const Trace below = run_for(law, beta_c - dbeta, dt, T, fit_from);
    const Trace above = run_for(law, beta_c + dbeta, dt, T, fit_from);
    std::printf("critical %-22s beta_c %.5f deg: below acc %+.3e v %+.3e | above acc %.6e (exp %.6e, rel %+.1e)\n",
                law.name.c_str(), beta_c / kDeg, below.acc, below.v, above.acc, A_above, above.acc / A_above - 1);
    // Holds below.
    EXPECT_LT(std::fabs(below.acc), 0.02 * A_above);
    if (!rigid_plastic) {
      EXPECT_LT(std::fabs(below.v), 1e-9);
    }
    // Rolls above.
    EXPECT_NEAR(above.acc, A_above, 1e-4 * A_above);
    EXPECT_GT(above.v, 0.5 * A_above * T);
  }
}

// jiang_brittle (after_break = open): the same cap (M0 = F_n B/6), but the spring breaks once |theta_r| passes
// theta_r0 = M0/K_m. Above the critical angle the contact breaks and the disc rolls freely: dv/dt = m g a^2
// sin(beta)/(I + m a^2). Just below it (beta_c - 0.015 degrees, G/M0 = 0.9974) a sudden load breaks it too, with every
// damping tried (linear.zeta up to 20, coulomb.zeta_t up to 5): the start-up transient takes the trial couple (spring +
// dashpot, the disc's inertia on top of G) past M0 at some step, the spring-slider caps and resets theta_r to
// theta_r0, and the next increment breaks the contact. That is the rule of docs/physics.md section 3, not a defect:
// jiang_plastic under the same load yields too (it comes to rest with theta 10 to 60 times its static value,
// depending on the damping) and then holds. So the hold is shown where the load leaves room for the transient
// (5 degrees, G/M0 = 0.875, heavily damped: linear.zeta = 10, mu_m = 6.8e-3 N m s, which needs dt = 1e-5).
TEST(Incline, JiangBrittleHoldsBelowAndBreaksAboveCriticalAngle) {
  LawSetup law = jiang("jiang_brittle", false);
  law.overrides.push_back("--jiang.after_break=open");  // broken for good: free rolling above beta_c
  law.overrides.push_back("--linear.zeta=10");
  const double beta_c = critical_angle(law);
  {
    const double beta = 5.0 * kDeg;
    const Trace r = run_for(law, beta, 1e-5, 0.5, 0.25);
    const double a = lever(beta);
    const double K = law.stiffness(normal_force(beta));
    const double x_exp = kWeight * std::sin(beta) * (1.0 / kKs + a * a / K);
    std::printf("jiang_brittle beta 5: x = %.9e (exp %.9e) theta = %.9e (exp %.9e)\n", r.x, x_exp, r.theta,
                -drive(beta) / K);
    EXPECT_NEAR(r.x, x_exp, 1e-4 * x_exp);
    EXPECT_NEAR(r.theta, -drive(beta) / K, 1e-4 * drive(beta) / K);
  }
  {
    const double beta = beta_c + 0.015 * kDeg;
    const Trace r = run_for(law, beta, 1e-5, 0.5, 0.1);
    const double a = lever(beta);
    const double A_free = kWeight * a * a * std::sin(beta) / (kInertia + kMass * a * a);
    std::printf("jiang_brittle above beta_c: acc %.6e (free rolling %.6e)\n", r.acc, A_free);
    EXPECT_NEAR(r.acc, A_free, 1e-4 * A_free);
  }
}

// Well above the critical angle (10 degrees; the needed friction |F_t| = 0.25 N stays below mu F_n = 1.0 N, so
// the disc rolls without slip): dv/dt = (m g a^2 sin(beta) - M_max a)/(I + m a^2), fitted over [0.1, 0.5] s,
// 1e-4 relative (the cap is exact once the disc rolls; the start-up transient of the tangential spring
// averages out).
TEST(Incline, RollingAccelerationAboveCriticalAngle) {
  const double beta = 10.0 * kDeg, dt = 5e-5;
  for (const LawSetup& law :
       {jiang("jiang_plastic", true), wang(true), alonso_marroquin(true), iwashita_oda(true),
        displacement_damping(true), constant_torque(), force_proportional(), jiang("jiang_plastic", false), wang(false),
        alonso_marroquin(false), iwashita_oda(false), displacement_damping(false)}) {
    SCOPED_TRACE(law.name);
    const double A = rolling_acceleration(law, beta);
    const Trace r = run_for(law, beta, dt, 0.5, 0.1);
    std::printf("rolling %-22s acc %.8e (exp %.8e, rel %+.1e)\n", law.name.c_str(), r.acc, A, r.acc / A - 1);
    EXPECT_NEAR(r.acc, A, 1e-4 * A);
  }
}

// Below the critical angle (4 degrees, G = 0.70 M_max): constant_torque and force_proportional cannot hold the
// disc. Their couple depends only on sign(omega), so the spin chatters about zero and the disc creeps downhill
// at a mean speed proportional to dt: halving dt halves it (within 10 %; measured ratios 2.02 and 2.03). With
// the default moment limiter (f_lim = 0.08) constant_torque is a viscous couple -f_lim I omega/dt near rest and
// creeps at exactly v = a G dt/(f_lim I), G = m g a sin(beta) (1e-6 relative; measured 1e-12). An
// elastic-plastic law under the same load holds: zero mean creep (with rolling damping it stops; without, it
// oscillates about a fixed point).
// Mean creep speed: the mean position over [1.5, 2.0] s minus that over [1.0, 1.5] s, over 0.5 s.
TEST(Incline, RigidPlasticLawsCreepAtASpeedProportionalToDt) {
  const double beta = 4.0 * kDeg, dt = 5e-5, T = 2.0;
  const Windows late{1.0, 1.5, 1.5, 2.0};
  const double a = lever(beta);
  double reference = INFINITY;  // the smallest creep speed of a rigid-plastic law
  for (const LawSetup& law : {constant_torque(), force_proportional()}) {
    SCOPED_TRACE(law.name);
    const Trace coarse = run_for(law, beta, dt, T, 1.0, late);
    const Trace fine = run_for(law, beta, 0.5 * dt, T, 1.0, late);
    std::printf("creep %-22s dt %.1e: %.6e m/s, dt/2: %.6e m/s, ratio %.4f\n", law.name.c_str(), dt, coarse.creep,
                fine.creep, coarse.creep / fine.creep);
    EXPECT_GT(fine.creep, 0.0);
    EXPECT_NEAR(coarse.creep / fine.creep, 2.0, 0.2);
    reference = std::min(reference, fine.creep);
  }
  {
    const LawSetup law = constant_torque(0.08);
    SCOPED_TRACE("constant_torque f_lim = 0.08");
    for (double h : {dt, 0.5 * dt}) {
      const Trace r = run_for(law, beta, h, T, 1.0, late);
      const double v_exp = a * drive(beta) * h / (0.08 * kInertia);
      std::printf("creep constant_torque f_lim 0.08 dt %.2e: %.9e m/s (exp %.9e, rel %+.1e), final v rel %+.1e\n", h,
                  r.creep, v_exp, r.creep / v_exp - 1, r.v / v_exp - 1);
      EXPECT_NEAR(r.creep, v_exp, 1e-6 * v_exp);
      EXPECT_NEAR(r.v, v_exp, 1e-6 * v_exp);
    }
  }
  for (const LawSetup& law : {jiang("jiang_plastic", true), wang(true), alonso_marroquin(true), iwashita_oda(true),
                              displacement_damping(true)}) {
    SCOPED_TRACE(law.name);
    const Trace r = run_for(law, beta, dt, T, 1.0, late);
    std::printf("creep %-22s (damped): %.3e m/s\n", law.name.c_str(), r.creep);
    EXPECT_LT(std::fabs(r.creep), 1e-9 * reference);
  }
  for (const LawSetup& law :
       {jiang("jiang_plastic", false), wang(false), alonso_marroquin(false), iwashita_oda(false)}) {
    SCOPED_TRACE(law.name);
    // Undamped, the disc oscillates about its rest point: the window means differ by a bounded amount, so the
    // apparent creep falls with the distance between the windows instead of persisting.
    const Trace near = run_for(law, beta, dt, T, 1.0, {0.2, 0.6, 0.6, 1.0});
    const Trace far = run_for(law, beta, dt, T, 1.0, {0.2, 0.6, 1.6, 2.0});
    std::printf("creep %-22s (undamped): %.3e m/s (windows 0.4 s apart), %.3e m/s (1.4 s apart)\n", law.name.c_str(),
                near.creep, far.creep);
    EXPECT_LT(std::fabs(near.creep), 0.02 * reference);
    EXPECT_LT(std::fabs(far.creep), 0.02 * reference);
  }
}

}  // namespace
}  // namespace rondel
