// The alonso_marroquin rolling law (W15 "model 2"), docs/validation.md section 10: the contact-point velocities
// s1, s2 and the rolling velocity V_r2 of the validation table against `wang`'s V_r, their objectivity (frame
// rotations of 37 and 137 degrees, a drift, superposed rigid spins), and the spring-slider on V_r2 (loading,
// the capping rule, the ledger's plastic/dashpot split, the couple held while the contact slides).
// Expected values are computed here from the formulas of docs/validation.md section 10; tolerance 1e-12
// relative, or 1e-15 absolute where the expected value is 0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"
#include "physics/RollingAlonsoMarroquin.hpp"
#include "physics/RollingIwashitaOda.hpp"
#include "physics/RollingWang.hpp"

namespace rondel {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRel = 1e-12;
constexpr double kZero = 1e-15;
constexpr double kR1 = 0.01;
constexpr double kDensity = 2650.0;

double disc_mass(double R) { return kDensity * kPi * R * R; }
double disc_inertia(double R) { return 0.5 * disc_mass(R) * R * R; }
Vec2 unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
Vec2 rotate(Vec2 a, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}

// One contact at one instant: two discs, or disc 1 on a wall (v2 = the wall's velocity, n_wall from the disc
// centre towards the wall). `dist` is the exact centre distance (centre-to-wall distance at a wall), passed as
// such because a frame change leaves it unchanged (test_kinematics.cpp explains why).
struct State {
  bool wall = false;
  double R1 = kR1, R2 = kR1, dist = 0.0;
  Vec2 x1, x2, v1, v2, n_wall;
  double w1 = 0.0, w2 = 0.0;
};

ContactKinematics kinematics(const State& s) {
  if (s.wall) return disc_wall_kinematics(s.n_wall, s.dist, s.R1, s.v1, s.v2, s.w1);
  return disc_disc_kinematics(s.x2 - s.x1, s.dist, s.R1, s.R2, s.v1, s.v2, s.w1, s.w2);
}
ContactBodies bodies(const State& s) {
  return s.wall ? disc_wall_bodies(disc_mass(s.R1), disc_inertia(s.R1))
                : disc_disc_bodies(disc_mass(s.R1), disc_mass(s.R2), disc_inertia(s.R1), disc_inertia(s.R2));
}
AlonsoMarroquinRates rates(const State& s) { return alonso_marroquin_rates(kinematics(s), s.w1, s.w2); }

// Two discs with overlap u_n along `angle` from disc 1, at rest.
State pair(double R2, double u_n, double angle = 0.7) {
  State s;
  s.R2 = R2;
  s.dist = kR1 + R2 - u_n;
  s.x1 = {0.002, -0.001};
  s.x2 = s.x1 + s.dist * unit(angle);
  return s;
}
// Disc 1 on a wall at overlap u_n, the wall in direction `angle` from the centre; at rest.
State on_wall(double u_n, double angle = -1.9) {
  State s;
  s.wall = true;
  s.R2 = INFINITY;
  s.dist = kR1 - u_n;
  s.x1 = {0.001, 0.003};
  s.n_wall = unit(angle);
  return s;
}
Vec2 tangent(const State& s) { return perp(s.wall ? s.n_wall : (1.0 / s.dist) * (s.x2 - s.x1)); }

// The size of the terms that make up s1 and s2: rounding leaves a zero at ~eps times this.
double scale(const State& s) {
  const double v = std::sqrt(dot(s.v1, s.v1)) + std::sqrt(dot(s.v2, s.v2));
  if (s.wall) return kR1 * std::fabs(s.w1) + v;
  return kR1 * std::fabs(s.w1) + s.R2 * std::fabs(s.w2) + 2.0 * v;
}

::testing::AssertionResult near(double got, double expected, double zero_scale = 1.0) {
  const double tol = expected == 0.0 ? kZero * zero_scale : kRel * std::fabs(expected);
  if (std::fabs(got - expected) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << got << " vs expected " << expected << " (diff " << got - expected
                                       << ", tolerance " << tol << ")";
}
// 1e-12 relative to the larger of the expected value and `scale` (a quantity formed by a difference).
::testing::AssertionResult near_scaled(double got, double expected, double scale) {
  const double tol = kRel * std::max(std::fabs(expected), scale);
  if (std::fabs(got - expected) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << got << " vs expected " << expected << " (diff " << got - expected
                                       << ", tolerance " << tol << ")";
}

const double kRadii2[] = {kR1, 2 * kR1, 10 * kR1, 100 * kR1};
const double kOverlaps[] = {0.0, 1e-5};

// ---------------------------------------------------------------------------------------------------------
// The validation table of docs/validation.md section 10.

TEST(AlonsoMarroquin, PureRollingCentresFixedGivesR1Omega1LikeWang) {
  const double w1 = 10.0;
  for (double R2 : kRadii2)
    for (double u_n : kOverlaps) {
      SCOPED_TRACE("R2 " + std::to_string(R2) + " u_n " + std::to_string(u_n));
      State s = pair(R2, u_n);
      s.w1 = w1;
      s.w2 = -kR1 * w1 / R2;  // R1 omega1 = -R2 omega2
      const AlonsoMarroquinRates r = rates(s);
      EXPECT_TRUE(near(r.s1, kR1 * w1));
      EXPECT_TRUE(near(r.s2, -R2 * s.w2));
      EXPECT_TRUE(near(r.V_r2, kR1 * w1));
      EXPECT_TRUE(near(kinematics(s).V_r, kR1 * w1));  // wang: the same
    }
}

TEST(AlonsoMarroquin, PureSlidingCentresFixedGivesZeroLikeWang) {
  const double w = 10.0;
  for (double R2 : {2 * kR1, 10 * kR1, 100 * kR1})
    for (double u_n : kOverlaps) {
      SCOPED_TRACE("R2 " + std::to_string(R2) + " u_n " + std::to_string(u_n));
      State s = pair(R2, u_n);
      s.w1 = s.w2 = w;
      const AlonsoMarroquinRates r = rates(s);
      EXPECT_TRUE(near(r.s1, kR1 * w));
      EXPECT_TRUE(near(r.s2, -R2 * w));
      EXPECT_EQ(r.V_r2, 0.0);                          // different signs
      EXPECT_TRUE(near(kinematics(s).V_r, 0.0, 1.0));  // wang: 0
    }
}

// A touching pair (the table's case) and, with |d| in betadot, an overlapping one: s1 = s2 = 0 to rounding.
TEST(AlonsoMarroquin, RigidRotationGivesZero) {
  const double Omega = 5.0;
  const Vec2 c{0.031, -0.017};
  for (double R2 : kRadii2)
    for (double u_n : kOverlaps)
      for (double turn : {0.0, 0.4, 2.5}) {
        SCOPED_TRACE("R2 " + std::to_string(R2) + " u_n " + std::to_string(u_n) + " turn " + std::to_string(turn));
        State s = pair(R2, u_n, 0.3);
        for (auto [x, v] : {std::pair{&s.x1, &s.v1}, std::pair{&s.x2, &s.v2}}) {
          *x = c + rotate(*x - c, turn);
          *v = Omega * perp(*x - c);
        }
        s.w1 = s.w2 = Omega;
        // 1e-15 m/s absolute, or 1e-15 of the cancelling terms where they exceed 1 m/s (R2 = 1 m: R2 Omega = 5 m/s).
        const double terms = std::max(1.0, scale(s));
        const AlonsoMarroquinRates r = rates(s);
        EXPECT_TRUE(near(r.s1, 0.0, terms));
        EXPECT_TRUE(near(r.s2, 0.0, terms));
        EXPECT_TRUE(near(r.V_r2, 0.0, terms));
        EXPECT_TRUE(near(kinematics(s).V_r, 0.0, terms));
      }
}

TEST(AlonsoMarroquin, DiscTranslatingOnWallWithoutRotationGivesZero) {
  for (double v : {1.0, -0.3}) {
    State s = on_wall(2e-6);
    s.v1 = v * tangent(s);
    const AlonsoMarroquinRates r = rates(s);
    EXPECT_EQ(r.s1, 0.0);
    EXPECT_TRUE(near(r.s2, -v));
    EXPECT_EQ(r.V_r2, 0.0);
    EXPECT_EQ(kinematics(s).V_r, 0.0);
  }
}

TEST(AlonsoMarroquin, DiscRollingOnWallWithoutSlipGivesR1Omega1LikeWang) {
  for (double w1 : {-200.0, 35.0}) {
    State s = on_wall(2e-6);
    s.w1 = w1;
    s.v1 = (-kR1 * w1) * tangent(s) + 0.3 * s.n_wall;  // V_t = -R1 omega1; a normal component changes nothing
    const AlonsoMarroquinRates r = rates(s);
    EXPECT_TRUE(near(r.s1, kR1 * w1));
    EXPECT_TRUE(near(r.s2, kR1 * w1));
    EXPECT_TRUE(near(r.V_r2, kR1 * w1));
    EXPECT_TRUE(near(kinematics(s).V_r, kR1 * w1));
    // The wall may move: only the relative velocity counts.
    State moving = s;
    moving.v2 = Vec2{0.4, -0.2};
    moving.v1 = s.v1 + moving.v2;
    EXPECT_TRUE(near(rates(moving).V_r2, kR1 * w1));
  }
}

// Equal discs, centres fixed: omega2 = -2 gives s1 = 10 R, s2 = 2 R and V_r2 = 2 R (wang: R/2 (10 + 2) = 6 R);
// omega2 = +2 gives s2 = -2 R: different signs, V_r2 = 0 (wang: 4 R).
TEST(AlonsoMarroquin, UnequalSpeedsTakeTheCommonPartOrNothing) {
  const double R = kR1;
  for (double u_n : kOverlaps) {
    SCOPED_TRACE("u_n " + std::to_string(u_n));
    State s = pair(R, u_n);
    s.w1 = 10.0;
    s.w2 = -2.0;
    AlonsoMarroquinRates r = rates(s);
    EXPECT_TRUE(near(r.s1, 10 * R));
    EXPECT_TRUE(near(r.s2, 2 * R));
    EXPECT_TRUE(near(r.V_r2, 2 * R));
    EXPECT_TRUE(near(kinematics(s).V_r, 6 * R));
    s.w2 = 2.0;
    r = rates(s);
    EXPECT_TRUE(near(r.s1, 10 * R));
    EXPECT_TRUE(near(r.s2, -2 * R));
    EXPECT_EQ(r.V_r2, 0.0);
    EXPECT_TRUE(near(kinematics(s).V_r, 4 * R));
    // The same mirrored: the sign follows s1 (and s2).
    s.w1 = -10.0;
    s.w2 = 2.0;
    EXPECT_TRUE(near(rates(s).V_r2, -2 * R));
  }
}

// s1 and s2 are the rates of the contact-point arcs of iwashita_oda (da/dt and -db/dt, W15 Eqs. 17, 19a):
// that law's rolling rate r' dtheta_r/dt is their average, for any motion of a disc pair.
TEST(AlonsoMarroquin, ContactPointVelocitiesAreTheArcRatesOfIwashitaOda) {
  for (double R2 : kRadii2) {
    State s = pair(R2, 1e-5, 1.2);
    s.v1 = {0.3, -0.1};
    s.v2 = {-0.05, 0.2};
    s.w1 = 7.0;
    s.w2 = -3.0;
    const ContactKinematics k = kinematics(s);
    const AlonsoMarroquinRates r = rates(s);
    const double r_prime = 0.5 * (kR1 + R2);
    EXPECT_NEAR(r_prime * iwashita_oda_rate(k, s.w1, s.w2), 0.5 * (r.s1 + r.s2), kRel * scale(s));
  }
}

// ---------------------------------------------------------------------------------------------------------
// Objectivity: s1, s2 and V_r2 (and the couple that the law builds on them, step after step) are unchanged by
// rotating every position and velocity by 37 or 137 degrees about a point, by a uniform drift and, for a disc
// pair, by a superposed rigid spin Omega (omega_i += Omega, v_i += Omega z x (x_i - c)). Walls translate only,
// so wall states get rotations and drifts.

struct Frame {
  double alpha = 0.0, Omega = 0.0;
  Vec2 c{0.0123, -0.0071}, U{0.0, 0.0};
};

State transform(const State& s, const Frame& f) {
  auto pos = [&](Vec2 x) { return f.c + rotate(x - f.c, f.alpha); };
  auto vel = [&](Vec2 x, Vec2 v) { return rotate(v + f.Omega * perp(x - f.c), f.alpha) + f.U; };
  State o = s;
  o.x1 = pos(s.x1);
  o.v1 = vel(s.x1, s.v1);
  o.w1 = s.w1 + f.Omega;
  if (s.wall) {
    o.n_wall = rotate(s.n_wall, f.alpha);
    o.v2 = rotate(s.v2, f.alpha) + f.U;
  } else {
    o.x2 = pos(s.x2);
    o.v2 = vel(s.x2, s.v2);
    o.w2 = s.w2 + f.Omega;
  }
  return o;
}

// States with every sign combination: the table's motions plus general ones (an overlap, a centre tangential
// velocity, an approach velocity).
std::vector<State> objectivity_states() {
  std::vector<State> out;
  for (double R2 : kRadii2)
    for (double u_n : kOverlaps) {
      State s = pair(R2, u_n, 2.1);
      s.w1 = 10.0, s.w2 = -kR1 * 10.0 / R2;  // pure rolling
      out.push_back(s);
      s.w1 = s.w2 = 10.0;  // pure sliding
      out.push_back(s);
      s.v1 = 0.05 * tangent(s) + 0.02 * (1.0 / s.dist) * (s.x2 - s.x1);  // V_t = 0.05, approaching
      s.w1 = 10.0, s.w2 = -4.0;
      out.push_back(s);
      s.w1 = -3.0, s.w2 = -8.0;
      out.push_back(s);
      s.v1 = -0.2 * tangent(s);
      s.w1 = 15.0, s.w2 = 9.0;  // s1 > 0 and s2 > 0
      out.push_back(s);
    }
  for (double u_n : kOverlaps) {
    State s = on_wall(u_n + 2e-6);
    s.w1 = -200.0;
    s.v1 = 2.0 * tangent(s);  // rolling without slip
    out.push_back(s);
    s.w1 = 0.0;  // translating
    out.push_back(s);
    s.w1 = -150.0;  // rolling and slipping
    out.push_back(s);
  }
  return out;
}

// Runs the law `steps` times on the state (a held motion) and returns the couples on disc 1.
template <class Law>
std::vector<double> couples(const State& s, int steps) {
  ContactParams p;
  p.k_r = 3e4;
  p.mu_r = 0.1;
  p.c_r = 5.0;
  double x_r = 0.0;
  const ContactKinematics k = kinematics(s);
  const ContactBodies b = bodies(s);
  std::vector<double> M;
  // F_n = 10 N: the cap (1 N) is reached within the run by the faster motions, not by the slower ones.
  for (int n = 0; n < steps; ++n) M.push_back(Law::moment(ContactInput{p, b, k, 10.0, 1e-5, s.w1, s.w2}, {x_r}).M1);
  return M;
}

TEST(AlonsoMarroquin, ObjectiveUnderRotationDriftAndRigidSpin) {
  const double deg = kPi / 180.0;
  int compared = 0, nonzero = 0;
  for (const State& s : objectivity_states()) {
    const AlonsoMarroquinRates ref = rates(s);
    const std::vector<double> M_ref = couples<RollingAlonsoMarroquin>(s, 40);
    nonzero += ref.V_r2 != 0.0;
    std::vector<Frame> frames;
    for (double alpha : {37 * deg, 137 * deg}) {
      frames.push_back({alpha, 0.0});
      frames.push_back({alpha, 0.0, {0.0123, -0.0071}, {0.3, -0.7}});
      if (!s.wall)
        for (double Omega : {3.0, -7.5}) frames.push_back({alpha, Omega, {0.0123, -0.0071}, {0.3, -0.7}});
    }
    for (const Frame& f : frames) {
      const State o = transform(s, f);
      const AlonsoMarroquinRates got = rates(o);
      const double sc = std::max(scale(s), scale(o));
      SCOPED_TRACE("alpha " + std::to_string(f.alpha) + " Omega " + std::to_string(f.Omega) + " wall " +
                   std::to_string(s.wall) + " R2 " + std::to_string(s.R2));
      EXPECT_NEAR(got.s1, ref.s1, kRel * std::max(std::fabs(ref.s1), sc));
      EXPECT_NEAR(got.s2, ref.s2, kRel * std::max(std::fabs(ref.s2), sc));
      EXPECT_NEAR(got.V_r2, ref.V_r2, kRel * std::max(std::fabs(ref.V_r2), sc));
      const std::vector<double> M = couples<RollingAlonsoMarroquin>(o, 40);
      for (std::size_t n = 0; n < M.size(); ++n) {
        // The couple is R* (k_r x_r + c_r V_r2) below the cap: its rounding follows the scale of V_r2.
        const double M_scale = 0.5 * kR1 * (3e4 * 40 * 1e-5 + 5.0) * sc;
        EXPECT_NEAR(M[n], M_ref[n], kRel * std::max(std::fabs(M_ref[n]), M_scale)) << "step " << n;
      }
      ++compared;
    }
  }
  EXPECT_GT(compared, 100);
  EXPECT_GT(nonzero, 15);  // the comparisons compared rolling contacts too
}

// The check above can fail: W15 Eqs. 23-24 with R1 + R2 in place of |d| are not objective once the discs
// overlap (a superposed spin Omega moves s1 by R1 Omega u_n/(R1 + R2)); with |d| = R1 + R2 - u_n they are.
// At a touching pair the two forms agree.
TEST(AlonsoMarroquin, DistanceNotRadiusSumKeepsTheOverlappingPairObjective) {
  const double Omega = 3.0;
  auto literal_s1 = [](const State& s) {
    return s.R1 * s.w1 + s.R1 / (s.R1 + s.R2) * kinematics(s).V_t;  // W15 Eq. 23 as printed, in this frame
  };
  for (double u_n : kOverlaps) {
    State s = pair(2 * kR1, u_n, 0.9);
    s.w1 = 10.0;
    s.w2 = -5.0;
    s.v1 = 0.05 * tangent(s);
    const State spun = transform(s, {0.0, Omega});
    EXPECT_NEAR(rates(spun).s1, rates(s).s1, kRel * scale(spun));
    const double drift = literal_s1(spun) - literal_s1(s);
    EXPECT_NEAR(drift, kR1 * Omega * u_n / (3 * kR1), 1e-12 * scale(spun));
    if (u_n == 0.0) {
      EXPECT_NEAR(literal_s1(s), rates(s).s1, kZero);
    } else {
      EXPECT_GT(std::fabs(drift), 1e-5 * std::fabs(rates(s).s1));  // not a rounding effect
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// The spring-slider on V_r2: x_r += V_r2 dt, trial T_r = -k_r x_r - c_r V_r2, cap mu_r F_n by the capping rule
// (T_r = cap sign(trial), x_r = -T_r/k_r), M = R* T_r on disc 1 and -M on disc 2; the ledger books the cap
// times the spring's slip when capped and c_r V_r2^2 dt otherwise, as `wang`.

struct Expected {
  double x_r = 0.0, M = 0.0, plastic = 0.0, dashpot = 0.0;
  bool capped = false;
};
// One step of the spring-slider of docs/physics.md section 3, written out.
Expected expected_step(const ContactParams& p, double R_star, double F_n, double V, double dt, double x_r) {
  Expected e;
  e.x_r = x_r + V * dt;
  const double trial = -p.k_r * e.x_r - p.c_r * V;
  const double cap = p.mu_r * F_n;
  double T = trial;
  if (std::fabs(trial) > cap) {
    T = trial > 0 ? cap : -cap;
    const double reset = -T / p.k_r;
    e.plastic = std::fabs(T) * std::fabs(e.x_r - reset);
    e.x_r = reset;
    e.capped = true;
  } else {
    e.dashpot = p.c_r * V * V * dt;
  }
  e.M = R_star * T;
  return e;
}

TEST(AlonsoMarroquin, SpringSliderLoadsYieldsAtCapAndBooksLikeWang) {
  ContactParams p;
  p.k_r = 3e4;
  p.mu_r = 0.1;
  p.c_r = 0.5;
  const double F_n = 1.0, dt = 1e-7, w1 = 10.0;
  for (double R2 : {kR1, 4 * kR1, static_cast<double>(INFINITY)}) {
    SCOPED_TRACE("R2 " + std::to_string(R2));
    const bool wall = std::isinf(R2);
    State s = wall ? on_wall(1e-6) : pair(R2, 1e-6);
    s.w1 = w1;
    if (wall)
      s.v1 = (-kR1 * w1) * tangent(s);  // rolling without slip
    else
      s.w2 = -kR1 * w1 / R2;  // pure rolling, centres fixed
    const ContactKinematics k = kinematics(s);
    const ContactBodies b = bodies(s);
    const double V = kR1 * w1, R_star = wall ? kR1 : reduced_radius(kR1, R2);
    // The first capped step: k_r n V dt + c_r V > mu_r F_n.
    const int n_yield = static_cast<int>(std::floor((p.mu_r * F_n - p.c_r * V) / (p.k_r * V * dt))) + 1;
    ASSERT_GT(n_yield, 100);
    double x_am = 0.0, x_wang = 0.0, x_exp = 0.0;
    const ContactInput in{p, b, k, F_n, dt, s.w1, s.w2};
    int first_capped = -1;
    double dashpot = 0.0;
    for (int n = 1; n <= n_yield + 50; ++n) {
      const RollingCouple am = RollingAlonsoMarroquin::moment(in, {x_am});
      const RollingCouple wa = RollingWang::moment(in, {x_wang});
      const Expected e = expected_step(p, R_star, F_n, V, dt, x_exp);
      x_exp = e.x_r;
      ASSERT_TRUE(near(x_am, e.x_r)) << "step " << n;
      ASSERT_TRUE(near(am.M1, e.M)) << "step " << n;
      ASSERT_EQ(am.M2, -am.M1);
      // The slip of a capped step is a difference of two springs: compared relative to a step's work.
      const double work = p.mu_r * F_n * V * dt;
      ASSERT_TRUE(near_scaled(am.plastic, e.plastic, work)) << "step " << n;
      ASSERT_TRUE(near_scaled(am.dashpot, e.dashpot, work)) << "step " << n;
      // wang in pure rolling: the same couple, spring and ledger terms.
      ASSERT_TRUE(near(x_am, x_wang)) << "step " << n;
      ASSERT_TRUE(near(am.M1, wa.M1)) << "step " << n;
      ASSERT_TRUE(near_scaled(am.plastic, wa.plastic, work)) << "step " << n;
      ASSERT_TRUE(near_scaled(am.dashpot, wa.dashpot, work)) << "step " << n;
      if (e.capped && first_capped < 0) first_capped = n;
      // After the first capped step the spring slips by V dt a step: the cap's work is mu_r F_n V dt.
      if (first_capped > 0 && n > first_capped) {
        ASSERT_TRUE(near_scaled(am.plastic, work, work)) << "step " << n;
      }
      dashpot += am.dashpot;
    }
    EXPECT_EQ(first_capped, n_yield);
    EXPECT_TRUE(near(x_am, p.mu_r * F_n / p.k_r));  // held at the cap: x_r = mu_r F_n/k_r
    EXPECT_TRUE(near(RollingAlonsoMarroquin::moment(in, {x_am}).M1, -R_star * p.mu_r * F_n));
    EXPECT_TRUE(near(RollingAlonsoMarroquin::cap(in), R_star * p.mu_r * F_n));
    EXPECT_TRUE(near(RollingAlonsoMarroquin::stored(in, {x_am}), 0.5 * p.k_r * x_am * x_am));
    // The dashpot worked in the elastic steps only.
    EXPECT_TRUE(near(dashpot, (n_yield - 1) * p.c_r * V * V * dt));
  }
}

// Once loaded, a contact that slides (or whose s1 and s2 have different signs) keeps its spring: the couple
// holds at -R* k_r x_r, nothing is booked; wang would unload or load it by R* (omega1 - omega2) dt.
TEST(AlonsoMarroquin, SpringHeldWhileSlidingOrOfDifferentSigns) {
  ContactParams p;
  p.k_r = 3e4;
  p.mu_r = 0.1;
  p.c_r = 0.5;
  const double F_n = 1.0, dt = 1e-7;
  State s = pair(2 * kR1, 1e-6);
  const ContactBodies b = bodies(s);
  double x_r = 0.0;
  s.w1 = 10.0, s.w2 = -5.0;  // pure rolling: load the spring
  for (int n = 0; n < 20; ++n) {
    const ContactKinematics k = kinematics(s);
    RollingAlonsoMarroquin::moment(ContactInput{p, b, k, F_n, dt, s.w1, s.w2}, {x_r});
  }
  const double loaded = x_r;
  ASSERT_GT(loaded, 0.0);
  ASSERT_LT(p.k_r * loaded + p.c_r * kR1 * 10.0, p.mu_r * F_n);  // below the cap
  for (auto [w1, w2] : {std::pair{10.0, 10.0}, std::pair{10.0, 2.0}, std::pair{-3.0, -7.0}}) {
    s.w1 = w1, s.w2 = w2;
    const ContactKinematics k = kinematics(s);
    const RollingCouple c = RollingAlonsoMarroquin::moment(ContactInput{p, b, k, F_n, dt, s.w1, s.w2}, {x_r});
    EXPECT_EQ(x_r, loaded);
    EXPECT_TRUE(near(c.M1, -reduced_radius(kR1, 2 * kR1) * p.k_r * loaded));
    EXPECT_EQ(c.plastic, 0.0);
    EXPECT_EQ(c.dashpot, 0.0);
  }
}

TEST(AlonsoMarroquin, SharesWangsBlockSpringAndCap) {
  EXPECT_EQ(RollingAlonsoMarroquin::block, RollingWang::block);
  ContactParams p;
  p.k_r = 2e4;
  p.c_r = 3.0;
  p.mu_r = 0.2;
  for (bool wall : {false, true}) {
    const ContactKinematics k = contact_geometry(kR1, 3 * kR1, wall);
    const ContactBodies b = wall ? disc_wall_bodies(1.0, 1e-4) : disc_disc_bodies(1.0, 9.0, 1e-4, 9e-3);
    const ContactInput in{p, b, k, 2.0};
    const RollingSpring a = RollingAlonsoMarroquin::spring(in), w = RollingWang::spring(in);
    EXPECT_EQ(a.K, w.K);
    EXPECT_EQ(a.C, w.C);
    EXPECT_EQ(RollingAlonsoMarroquin::cap(in), RollingWang::cap(in));
  }
}

}  // namespace
}  // namespace rondel
