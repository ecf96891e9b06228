// Stability test F4 (docs/validation.md section 5; docs/physics.md section 4). One contact, linear normal, coulomb
// tangential (mu large: it never slips) and jiang_plastic rolling (the cap F_n B/6 is far above the couple:
// the contact is held closed at the overlap u0 = 1e-4 R1 by a constant central preload k_n u0, which adds
// no stiffness at rest, and the motion is ~1e-4 u0), undamped:
//  - the exact largest angular frequency w_max of the coupled normal, tangential and rolling springs is the
//    largest eigenvalue of K v = w^2 M v (Eigen), K = k_n e e^T + k_s g g^T + K_m h h^T in the contact frame
//    (e: overlap, g: sliding displacement, h: relative rotation per generalised displacement);
//  - integrated with the library's own pieces (OneContactRig.hpp) from a small random velocity, the
//    contact stays bounded at dt = 0.98 * 2/w_max (mean energy over steps 9000-10000 within 1.1x of steps
//    0-1000) and blows up at 1.02 * 2/w_max (energy 10x within 200 steps, judged on 10-step means since
//    near 2/w the energy sampled at full steps swings up to 25x within one oscillation even when stable);
//  - the code's estimate contact_critical_step() is at or below 2/w_max and above 0.85 * 2/w_max.
// Radius ratios rho = R2/R1 in {1, 2, 10, 100} and a wall; delta in {0.3, 1, 3}; contact sets S and J.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "OneContactRig.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "physics/LawRegistry.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

using testing_rig::OneContactRig;

constexpr double kR1 = 0.005;        // the D5 disc (docs/validation.md section 0)
constexpr double kDensity = 2650.0;  // kg/m^3, thickness 1 m
constexpr double kOverlap = 1e-4;    // rest overlap u0 / R1

using test::ContactSet;
using test::kSetJ;
using test::kSetS;

// (set, rho (0 = wall), delta)
using F4Param = std::tuple<ContactSet, double, double>;

LawSelection f4_laws() {
  LawSelection laws;
  laws.normal = "linear";
  laws.tangential = "coulomb";
  laws.rolling = "jiang_plastic";
  return laws;
}

class F4 : public ::testing::TestWithParam<F4Param> {
 protected:
  void SetUp() override {
    const auto& [set, rho, delta] = GetParam();
    wall_ = rho == 0.0;
    R2_ = wall_ ? INFINITY : rho * kR1;
    p_.k_n = set.k_n;
    p_.k_s = set.k_s;
    p_.mu = 1e3;  // never slips
    p_.zeta_n = 0.0;
    p_.zeta_t = 0.0;
    p_.delta = delta;
    u0_ = kOverlap * kR1;
    w_max_ = exact_w_max();
  }

  OneContactRig make_rig() const { return OneContactRig(f4_laws(), p_, kR1, R2_, u0_, p_.k_n * u0_, {}, kDensity); }

  // Generalised coordinates in the contact frame: per body (displacement along n, along t, rotation).
  // u_n = u0 + q_n1 - q_n2; sliding displacement xi = q_t1 - q_t2 + a1 theta1 + a2 theta2;
  // relative rotation theta_r = theta1 - theta2. A wall has no coordinates.
  double exact_w_max() {
    OneContactRig rig = make_rig();
    const DiscStore& D = rig.discs();
    const int n_dof = wall_ ? 3 : 6;
    const double a1 = kR1 - 0.5 * u0_;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(n_dof), g = e, h = e;
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n_dof, n_dof);
    e(0) = 1.0;
    g(1) = 1.0;
    g(2) = a1;
    h(2) = 1.0;
    M.diagonal().head(3) << D.mass[0], D.mass[0], D.inertia[0];
    double r = 2.0 * kR1;
    if (!wall_) {
      const double a2 = R2_ - 0.5 * u0_;
      e(3) = -1.0;
      g(4) = -1.0;
      g(5) = a2;
      h(5) = -1.0;
      M.diagonal().tail(3) << D.mass[1], D.mass[1], D.inertia[1];
      r = 2.0 * kR1 * R2_ / (kR1 + R2_);
    }
    const double B = p_.delta * r;
    K_m_ = p_.k_n * B * B / 12.0;  // J05 Eq. 24 via docs/physics.md section 3
    const Eigen::MatrixXd K = p_.k_n * e * e.transpose() + p_.k_s * g * g.transpose() + K_m_ * h * h.transpose();
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver(K, M, Eigen::EigenvaluesOnly);
    EXPECT_EQ(solver.info(), Eigen::Success);
    M_ = M;
    return std::sqrt(solver.eigenvalues().maxCoeff());
  }

  // Runs `steps` steps at dt from a random velocity with about the same energy in every coordinate;
  // returns the energy after each step (index 0: the start). Stops early once the energy passes
  // `stop_factor` times the start.
  std::vector<double> run(double dt, int steps, double stop_factor, double* min_overlap) const {
    OneContactRig rig = make_rig();
    DiscStore& D = rig.discs();
    const auto& [set, rho, delta] = GetParam();
    std::mt19937_64 rng(static_cast<std::uint64_t>(1000 * rho + 10 * delta + set.k_n));
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const double E_dof = 1e-8 * 0.5 * p_.k_n * u0_ * u0_;  // motion ~1e-4 of the rest overlap
    const std::size_t bodies = wall_ ? 1 : 2;
    for (std::size_t i = 0; i < bodies; ++i) {
      const double vn = unit(rng) * std::sqrt(2.0 * E_dof / D.mass[i]);
      const double vt = unit(rng) * std::sqrt(2.0 * E_dof / D.mass[i]);
      D.velocity[i] = vn * rig.n + vt * rig.t;
      D.omega[i] = unit(rng) * std::sqrt(2.0 * E_dof / D.inertia[i]);
    }
    rig.start(dt);
    std::vector<double> E{rig.energy()};
    *min_overlap = rig.overlap();
    for (int s = 0; s < steps; ++s) {
      rig.step();
      E.push_back(rig.energy());
      *min_overlap = std::min(*min_overlap, rig.overlap());
      if (!(E.back() < stop_factor * E.front())) break;
    }
    return E;
  }

  std::string label() const {
    const auto& [set, rho, delta] = GetParam();
    char buf[96];
    if (wall_)
      std::snprintf(buf, sizeof buf, "set %s, wall, delta %g", set.name, delta);
    else
      std::snprintf(buf, sizeof buf, "set %s, rho %g, delta %g", set.name, rho, delta);
    return buf;
  }

  ContactParams p_;
  bool wall_ = false;
  double R2_ = 0.0, u0_ = 0.0, K_m_ = 0.0, w_max_ = 0.0;
  Eigen::MatrixXd M_;
};

double mean(const std::vector<double>& v, std::size_t from, std::size_t to) {
  double s = 0.0;
  for (std::size_t k = from; k < to; ++k) s += v[k];
  return s / static_cast<double>(to - from);
}

// At dt close to 2/w the energy sampled at full steps swings by up to 1/(1 - (w dt/2)^2) (25x at 0.98)
// within one oscillation, so "10x" is judged on the mean over 10 consecutive steps (which spans several
// oscillations of the fastest mode), against the mean of steps 0-9.
std::size_t steps_to_tenfold(const std::vector<double>& E, std::size_t limit) {
  constexpr std::size_t kWindow = 10;
  const double start = mean(E, 0, kWindow);
  for (std::size_t k = kWindow; k < E.size() && k <= limit; ++k)
    if (mean(E, k + 1 - kWindow, k + 1) >= 10.0 * start) return k;
  return 0;
}

TEST_P(F4, ExactFrequencyIsTheTangentialRollingOrNormalMode) {
  // Cross-check the eigen solver against the closed forms: the normal mode decouples (w_n^2 = k_n/m_eff),
  // and the tangential+rolling block is rank 2, whose largest eigenvalue is that of
  // [[k_s G, sqrt(k_s K_m) C], [sqrt(k_s K_m) C, K_m H]], G = g.M^-1.g, H = h.M^-1.h, C = g.M^-1.h.
  const double a1 = kR1 - 0.5 * u0_;
  const Eigen::VectorXd Minv = M_.diagonal().cwiseInverse();
  double G = Minv(0) + a1 * a1 * Minv(2), H = Minv(2), C = a1 * Minv(2), inv_m_eff = Minv(0);
  if (!wall_) {
    const double a2 = R2_ - 0.5 * u0_;
    G += Minv(3) + a2 * a2 * Minv(5);
    H += Minv(5);
    C -= a2 * Minv(5);
    inv_m_eff += Minv(3);
  }
  const double A = p_.k_s * G, Dg = K_m_ * H, X = std::sqrt(p_.k_s * K_m_) * C;
  const double lam_tr = 0.5 * (A + Dg) + std::sqrt(0.25 * (A - Dg) * (A - Dg) + X * X);
  const double w_closed = std::sqrt(std::max(lam_tr, p_.k_n * inv_m_eff));
  EXPECT_NEAR(w_max_, w_closed, 1e-10 * w_closed) << label();
}

TEST_P(F4, BoundedAt098OfExactLimit) {
  const double dt = 0.98 * 2.0 / w_max_;
  double min_overlap = 0.0;
  const std::vector<double> E = run(dt, 10000, 1e6, &min_overlap);
  ASSERT_EQ(E.size(), 10001u) << label() << ": energy passed 1e6 x its start";
  const double early = mean(E, 0, 1000), late = mean(E, 9000, 10000);
  const double peak = *std::max_element(E.begin(), E.end());
  std::printf(
      "[F4 %s] w_max = %.6g rad/s, dt = 0.98 x 2/w_max = %.6g s: mean energy steps 9000-10000 / "
      "0-1000 = %.5f, peak/start = %.3g\n",
      label().c_str(), w_max_, dt, late / early, peak / E.front());
  EXPECT_EQ(steps_to_tenfold(E, E.size()), 0u) << label() << ": the 10-step mean energy grew 10x at 0.98";
  EXPECT_GT(min_overlap, 0.0) << label() << ": the contact opened";
  EXPECT_LE(late / early, 1.1) << label();
  EXPECT_GE(late / early, 1.0 / 1.1) << label();
}

TEST_P(F4, BlowsUpAt102OfExactLimit) {
  const double dt = 1.02 * 2.0 / w_max_;
  double min_overlap = 0.0;
  const std::vector<double> E = run(dt, 200, 1e6, &min_overlap);
  const std::size_t steps = steps_to_tenfold(E, 200);
  std::printf(
      "[F4 %s] dt = 1.02 x 2/w_max: 10-step mean energy 10x its start after %zu steps; energy x%.3g "
      "after %zu steps\n",
      label().c_str(), steps, E.back() / E.front(), E.size() - 1);
  EXPECT_GT(steps, 0u) << label() << ": no 10x growth of the 10-step mean energy within 200 steps";
  EXPECT_GT(min_overlap, 0.0) << label() << ": the contact opened (the run left the linear regime)";
}

TEST_P(F4, CodeEstimateIsBelowAndWithin15PercentOfExact) {
  OneContactRig rig = make_rig();
  const DiscStore& D = rig.discs();
  const ContactBody a{D.mass[0], D.inertia[0], kR1};
  const ContactBody b = wall_ ? ContactBody{INFINITY, INFINITY, INFINITY} : ContactBody{D.mass[1], D.inertia[1], R2_};
  std::string mode;
  const double est = contact_critical_step(f4_laws(), p_, a, b, &mode);
  const double exact = 2.0 / w_max_;
  std::printf("[F4 %s] code estimate %.6g s (%s mode) = %.4f x exact 2/w_max = %.6g s\n", label().c_str(), est,
              mode.c_str(), est / exact, exact);
  EXPECT_LE(est, exact * (1.0 + 1e-12)) << label() << ": the estimate is not conservative";
  EXPECT_GT(est, 0.85 * exact) << label() << ": the estimate (" << mode << " mode) is " << est / exact
                               << " of the exact limit, more than 15 % below it";
}

std::string f4_name(const ::testing::TestParamInfo<F4Param>& info) {
  const auto& [set, rho, delta] = info.param;
  std::string s = std::string(set.name) + "_" + (rho == 0.0 ? std::string("wall") : "rho" + std::to_string(int(rho))) +
                  "_delta" + std::to_string(delta);
  s = s.substr(0, s.find_last_not_of('0') + 1);
  for (char& c : s)
    if (c == '.') c = 'p';
  if (s.back() == 'p') s.pop_back();
  return s;
}

INSTANTIATE_TEST_SUITE_P(Contacts, F4,
                         ::testing::Combine(::testing::Values(kSetS, kSetJ),
                                            ::testing::Values(1.0, 2.0, 10.0, 100.0, 0.0),
                                            ::testing::Values(0.3, 1.0, 3.0)),
                         f4_name);

}  // namespace
}  // namespace rondel
