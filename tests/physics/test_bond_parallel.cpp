// The parallel bond's law (physics/BondParallel.hpp, docs/physics.md section 12), docs/validation.md section 15, on
// two bonded D5 discs (lambda = 1: Rb = 5 mm, A = 0.01 m^2, I = A (2 Rb)^2/12; kb_n = 1e9 Pa/m, kb_s = 0.5e9 Pa/m)
// driven through the kinematics of the contact kernel:
//  - pulled apart at a constant speed: Fb_n = kb_n A delta (delta the separation since creation) to round-off, the
//    stored energy the work done on the bond, and the break in tension in the first step whose Fb_n/A reaches
//    sigma_c;
//  - spun at fixed centres: equal spins shear it (Fb_s = -kb_s A (a1 + a2) w t, no moment), opposite spins bend it
//    (Mb = -2 kb_n I w t, no shear force), and of two modes the one whose stress reaches its strength first breaks;
//  - a frame rotated by 37 degrees and a rigid spin superposed on the pair change no force (1e-12);
//  - the strengths drawn per bond: a function of the pair of gids alone, within mean (1 +- spread), mean and spread
//    of a uniform draw over 100,000 bonds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "physics/BondParallel.hpp"
#include "physics/ContactKinematics.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

constexpr double kR = test::d5::R;
constexpr double kDt = 1e-6;

ContactParams params() {
  ContactParams p;
  p.kb_n = 1e9, p.kb_s = 0.5e9;
  p.sigma_c = 1e4, p.tau_c = 1e4;
  return p;
}
const BondGeometry kG = BondGeometry::of(kR, kR, 1.0, 1.0);

// The kinematics of discs at x1, x2 with velocities and spins (disc 1 the lower gid).
ContactKinematics motion(Vec2 x1, Vec2 x2, Vec2 v1, Vec2 v2, double w1, double w2) {
  const Vec2 d = x2 - x1;
  return disc_disc_kinematics(d, std::sqrt(dot(d, d)), kR, kR, v1, v2, w1, w2);
}

TEST(BondParallel, TheGeometryOfItsSection) {
  EXPECT_DOUBLE_EQ(kG.Rb, kR);
  EXPECT_DOUBLE_EQ(kG.A, 2.0 * kR);
  EXPECT_DOUBLE_EQ(kG.I, std::pow(2.0 * kR, 3) / 12.0);
  const BondGeometry unequal = BondGeometry::of(0.004, 0.006, 0.5, 0.8);
  EXPECT_DOUBLE_EQ(unequal.Rb, 0.8 * 0.004);
  EXPECT_DOUBLE_EQ(unequal.A, 2.0 * 0.8 * 0.004 * 0.5);
}

TEST(BondParallel, PulledApartItCarriesKbnADeltaAndBreaksInTensionWhenSigmaReachesItsStrength) {
  ContactParams p = params();
  p.sigma_c = 1.0505e4;   // reached between steps: Fb_n/A grows by 10 Pa a step
  const double V = 0.01;  // disc 2 leaves at 1 cm/s along +x
  BondState s;
  double work = 0.0;
  int broke_at = -1;
  const int expected = static_cast<int>(std::ceil(p.sigma_c / (p.kb_n * V * kDt) - 1e-9));  // Fb_n/A = kb_n V dt s
  for (int step = 1; step <= 2 * expected && broke_at < 0; ++step) {
    const double x2 = 2.0 * kR + V * (step - 0.5) * kDt;  // the half-step position and velocity
    const BondStep b = bond_step(p, kG, motion({}, {x2, 0.0}, {}, {V, 0.0}, 0.0, 0.0), kDt, s, p.sigma_c, p.tau_c);
    work += 0.5 * (s.Fb_n + b.state.Fb_n) * V * kDt;
    s = b.state;
    const double delta = V * step * kDt;
    ASSERT_NEAR(s.Fb_n, p.kb_n * kG.A * delta, 1e-12 * p.kb_n * kG.A * delta) << "step " << step;
    EXPECT_EQ(s.Fb_s, 0.0);
    EXPECT_EQ(s.Mb, 0.0);
    EXPECT_NEAR(bond_stored(p, kG, s), work, 1e-12 * work);
    if (b.mode != BondMode::intact) {
      EXPECT_EQ(b.mode, BondMode::tension);
      EXPECT_GE(b.sigma, p.sigma_c);
      broke_at = step;
    } else {
      EXPECT_LT(s.Fb_n / kG.A, p.sigma_c) << "intact below its strength";
    }
  }
  EXPECT_EQ(broke_at, expected) << "the first step whose Fb_n/A reaches sigma_c";
}

TEST(BondParallel, SpunAtFixedCentresItShearsOrBendsAndTheFirstModeToReachItsStrengthBreaks) {
  const ContactParams p = params();
  const Vec2 x2{2.0 * kR, 0.0};
  const double w = 0.3;
  BondState shear, bend;
  for (int step = 1; step <= 50; ++step) {
    shear = bond_step(p, kG, motion({}, x2, {}, {}, w, w), kDt, shear, 1e30, 1e30).state;
    bend = bond_step(p, kG, motion({}, x2, {}, {}, w, -w), kDt, bend, 1e30, 1e30).state;
    const double t = step * kDt;
    ASSERT_NEAR(shear.Fb_s, -p.kb_s * kG.A * 2.0 * kR * w * t, 1e-12 * p.kb_s * kG.A * 2.0 * kR * w * t);
    EXPECT_EQ(shear.Mb, 0.0);
    EXPECT_EQ(shear.Fb_n, 0.0);
    ASSERT_NEAR(bend.Mb, -p.kb_n * kG.I * 2.0 * w * t, 1e-12 * p.kb_n * kG.I * 2.0 * w * t);
    EXPECT_EQ(bend.Fb_s, 0.0);
  }
  // Both at once (w1 = 2w, w2 = 0: shear and bending together); the strengths put the stress that grows faster
  // relative to its strength first: sigma = |Mb| Rb/I grows at kb_n Rb 2w, tau = |Fb_s|/A at kb_s (2 Rb) w.
  const double sigma_rate = p.kb_n * kG.Rb * 2.0 * w, tau_rate = p.kb_s * 2.0 * kR * w;
  for (const bool tension_first : {true, false}) {
    const double sigma_c = sigma_rate * 40 * kDt * (tension_first ? 1.0 : 2.0);
    const double tau_c = tau_rate * 40 * kDt * (tension_first ? 2.0 : 1.0);
    BondState s;
    BondMode mode = BondMode::intact;
    int step = 0;
    while (mode == BondMode::intact && step < 1000) {
      const BondStep b = bond_step(p, kG, motion({}, x2, {}, {}, 2.0 * w, 0.0), kDt, s, sigma_c, tau_c);
      s = b.state, mode = b.mode, ++step;
    }
    EXPECT_EQ(mode, tension_first ? BondMode::tension : BondMode::shear);
    EXPECT_NEAR(step, 40, 1) << "the step its stress reaches the strength";
  }
}

TEST(BondParallel, ARotatedFrameAndASuperposedSpinChangeNoForce) {
  const ContactParams p = params();
  const Vec2 x1{0.013, -0.021}, v1{0.02, -0.01}, v2{-0.01, 0.015};
  const double w1 = 7.0, w2 = -3.0, dist = 2.0 * kR - 1e-5;
  auto trace = [&](double angle, double Omega) {
    const double c = std::cos(angle), s = std::sin(angle);
    auto rot = [&](Vec2 a) { return Vec2{c * a.x - s * a.y, s * a.x + c * a.y}; };
    const Vec2 n = rot({std::cos(0.6), std::sin(0.6)});
    const Vec2 y1 = rot(x1), y2 = y1 + dist * n;
    const Vec2 c0{0.004, 0.011};  // the spin's centre
    const Vec2 u1 = rot(v1) + Omega * perp(y1 - c0), u2 = rot(v2) + Omega * perp(y2 - c0);
    std::vector<double> out;
    BondState st;
    for (int step = 0; step < 200; ++step) {
      st = bond_step(p, kG, motion(y1, y2, u1, u2, w1 + Omega, w2 + Omega), kDt, st, 1e30, 1e30).state;
      out.insert(out.end(), {st.Fb_n, st.Fb_s, st.Mb});
    }
    return out;
  };
  const std::vector<double> base = trace(0.0, 0.0);
  for (const auto& [angle, Omega] : {std::pair{37.0 * std::numbers::pi / 180.0, 0.0}, std::pair{0.0, 5.0},
                                     std::pair{137.0 * std::numbers::pi / 180.0, -11.0}}) {
    const std::vector<double> other = trace(angle, Omega);
    for (std::size_t i = 0; i < base.size(); ++i)
      ASSERT_NEAR(other[i], base[i], 1e-12 * std::max(1.0, std::fabs(base[i])))
          << "value " << i << ", angle " << angle << ", Omega " << Omega;
  }
}

TEST(BondParallel, EachBondsStrengthIsAFunctionOfItsPairOfGids) {
  EXPECT_EQ(bond_strength(1e6, 0.0, 3, 8, kTensileSalt), 1e6) << "no spread: the mean exactly";
  EXPECT_EQ(bond_strength(1e6, 0.3, 3, 8, kTensileSalt), bond_strength(1e6, 0.3, 3, 8, kTensileSalt));
  EXPECT_NE(bond_strength(1e6, 0.3, 3, 8, kTensileSalt), bond_strength(1e6, 0.3, 3, 9, kTensileSalt));
  EXPECT_NE(bond_strength(1e6, 0.3, 3, 8, kTensileSalt), bond_strength(1e6, 0.3, 3, 8, kShearSalt));
  double sum = 0.0, sum2 = 0.0, lo = 1e300, hi = 0.0;
  constexpr int kN = 100000;
  for (std::int64_t b = 0; b < kN; ++b) {
    const double s = bond_strength(1e6, 0.3, b, b + 1 + (b * 7919) % 13, kShearSalt);
    sum += s, sum2 += s * s, lo = std::min(lo, s), hi = std::max(hi, s);
  }
  const double mean = sum / kN, sd = std::sqrt(sum2 / kN - mean * mean);
  EXPECT_GE(lo, 0.7e6);
  EXPECT_LT(hi, 1.3e6);
  EXPECT_NEAR(mean, 1e6, 3e-3 * 1e6);
  EXPECT_NEAR(sd, 0.3e6 / std::sqrt(3.0), 1e-2 * 0.3e6 / std::sqrt(3.0)) << "uniform in mean (1 +- spread)";
}

}  // namespace
}  // namespace rondel
