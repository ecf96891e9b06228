// jiang_brittle (J05 Model 2) after a break, docs/validation.md section 6: a contact rolled at a constant
// relative rate with a constant normal force. With jiang.after_break = reform (the default) the couple is a
// sawtooth between 0 and M0 = F_n B/6: the spring loads from theta_r = 0, breaks when |theta_r| passes
// theta_r0 = 2 F_n/(k_n B) (M = 0 that step, the stored K_m theta_r^2/2 released), and restarts from 0 the next
// step, with the period theta_r0/thetadot_r (in steps: the breaking step is the first whose theta_r passes
// theta_r0). With open the couple stays 0 after the first break until the contact opens. Exact: the same
// arithmetic as the law (no dashpot: mu_m = 0). Every step's energy closes: the couple's trapezoid work
// -(M' + M) thetadot_r dt/2 is the change of the stored K_m theta_r^2/2 plus the release, to round-off, the
// breaking steps included (the release is the stored energy and the couple's work in the step's first half). And
// the key itself: its words, its default, a bad word refused naming the key and the words allowed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/LawTypes.hpp"
#include "physics/RollingJiangBrittle.hpp"

namespace rondel {
namespace {

constexpr double kR = 0.005, kKn = 1e6, kDelta = 0.3, kFn = 2.0, kRate = 0.5, kDt = 1e-4;

struct Rolled {
  std::vector<double> M;         // the couple on disc 1, step by step
  std::vector<double> released;  // the stored energy released at each step (0 but at a break)
  double worst_gap = 0.0;        // the largest |work - change of stored - release| of a step
};

// Two equal discs in contact along x, disc 1 spinning at kRate (thetadot_r = kRate), n_steps steps.
Rolled roll(double after_break, int n_steps) {
  ContactParams p;
  p.k_n = kKn;
  p.delta = kDelta;
  p.after_break = after_break;
  const double dist = 2.0 * kR - 1e-5;
  const ContactKinematics k = disc_disc_kinematics({dist, 0.0}, dist, kR, kR, {}, {}, kRate, 0.0);
  const ContactBodies b = disc_disc_bodies(1.0, 1.0, 1e-5, 1e-5);
  double theta_r = 0.0, broken = 0.0, M_prev = 0.0;
  Rolled out;
  for (int s = 0; s < n_steps; ++s) {
    const ContactInput in{p, b, k, kFn, kDt, kRate, 0.0, M_prev};
    const double stored_before = RollingJiangBrittle::stored(in, {theta_r, broken});
    const RollingCouple c = RollingJiangBrittle::moment(in, {theta_r, broken});
    const double taken = -0.5 * (M_prev + c.M1) * kRate * kDt;  // the couple's work on the discs, negated
    const double stored_after = RollingJiangBrittle::stored(in, {theta_r, broken});
    out.worst_gap =
        std::max(out.worst_gap, std::fabs(taken - (stored_after - stored_before) - c.released - c.plastic - c.dashpot));
    out.M.push_back(c.M1);
    out.released.push_back(c.released);
    M_prev = c.M1;
  }
  return out;
}

struct Expected {
  double K_m, M0, theta_r0;
  // The period theta_r0 / thetadot_r in steps: the steps from one break to the next, those that pass theta_r0 from 0.
  int period() const { return static_cast<int>(std::floor(theta_r0 / (kRate * kDt))) + 1; }
};
Expected expected() {
  const double B = kDelta * kR;  // r = 2 R1 R2/(R1 + R2) = R for equal discs
  return {kKn * B * B / 12.0, kFn * B / 6.0, 2.0 * kFn / (kKn * B)};
}

TEST(JiangBrittle, ReformIsASawtoothBetweenZeroAndTheCapWithItsPeriod) {
  const Expected e = expected();
  const Rolled r = roll(kAfterBreakReform, 200);
  // Replay the law's arithmetic: theta_r += thetadot dt; past theta_r0 a break (M = 0, theta_r = 0).
  double theta = 0.0;
  int breaks = 0, first_break = -1, second_break = -1;
  for (std::size_t s = 0; s < r.M.size(); ++s) {
    const double before = theta;
    theta += kRate * kDt;
    if (std::fabs(theta) > e.theta_r0) {
      EXPECT_EQ(r.M[s], 0.0) << "step " << s << ": a break carries no couple";
      // The stored energy and the work of the step's first half, 0.5 K_m theta_before thetadot dt.
      EXPECT_NEAR(r.released[s], 0.5 * e.K_m * before * before + 0.5 * e.K_m * before * kRate * kDt,
                  1e-12 * e.K_m * e.theta_r0 * e.theta_r0);
      if (breaks == 0) first_break = static_cast<int>(s);
      if (breaks == 1) second_break = static_cast<int>(s);
      ++breaks;
      theta = 0.0;
    } else {
      EXPECT_NEAR(r.M[s], -e.K_m * theta, 1e-12 * e.M0) << "step " << s;
      EXPECT_LE(std::fabs(r.M[s]), e.M0 * (1.0 + 1e-12));
      EXPECT_EQ(r.released[s], 0.0);
    }
  }
  const int period = e.period();
  std::printf("  reform: theta_r0 %.6e rad, M0 %.6e N m, %d breaks in 200 steps, every %d steps\n", e.theta_r0, e.M0,
              breaks, second_break - first_break);
  ASSERT_GE(breaks, 3);
  EXPECT_LE(r.worst_gap, 1e-12 * e.M0 * e.theta_r0) << "a step's energy does not close";
  EXPECT_EQ(first_break, period - 1);
  EXPECT_EQ(second_break - first_break, period);
  // The couple comes back near the cap before each break (the sawtooth's top).
  EXPECT_GT(std::fabs(r.M[static_cast<std::size_t>(first_break) - 1]), e.M0 * (1.0 - 2.0 / period));
}

TEST(JiangBrittle, OpenKeepsTheCoupleAtZeroAfterTheFirstBreak) {
  const Expected e = expected();
  const Rolled r = roll(kAfterBreakOpen, 200);
  EXPECT_LE(r.worst_gap, 1e-12 * e.M0 * e.theta_r0) << "a step's energy does not close";
  const int period = e.period();
  for (int s = 0; s < period - 1; ++s) EXPECT_NE(r.M[static_cast<std::size_t>(s)], 0.0) << "step " << s;
  for (std::size_t s = static_cast<std::size_t>(period) - 1; s < r.M.size(); ++s) {
    EXPECT_EQ(r.M[s], 0.0) << "step " << s;
    if (s >= static_cast<std::size_t>(period)) {
      EXPECT_EQ(r.released[s], 0.0) << "one release only";
    }
  }
}

std::string jiang_ini(const std::string& extra) {
  return "[run]\nsteps = 1\n[domain]\nxlo = 0\nxhi = 0.1\nylo = 0\nyhi = 0.1\n[material]\ndensity = 2650\n"
         "[linear]\nk_n = 1e6\n[coulomb]\nk_s = 3e5\nmu = 0.5\n[contact]\nrolling = jiang_brittle\n[jiang]\n"
         "delta = 0.3\n" +
         extra + "[scene]\ntype = lattice_square\nnx = 2\nny = 1\nradius = 0.005\nx0 = 0.01\ny0 = 0.01\n";
}

TEST(JiangBrittle, AfterBreakIsAWordReformByDefaultAndABadOneIsRefused) {
  EXPECT_EQ(parse_config_text(jiang_ini(""), {}).params.pair(0, 0).after_break, kAfterBreakReform);
  EXPECT_EQ(parse_config_text(jiang_ini("after_break = open\n"), {}).params.pair(0, 0).after_break, kAfterBreakOpen);
  EXPECT_EQ(parse_config_text(jiang_ini(""), {"--jiang.after_break=reform"}).params.pair(0, 0).after_break,
            kAfterBreakReform);
  for (const std::string bad : {"opened", "1", "nan", ""}) {
    try {
      parse_config_text(jiang_ini(""), {"--jiang.after_break=" + bad});
      ADD_FAILURE() << "'" << bad << "' accepted";
    } catch (const std::exception& ex) {
      const std::string what = ex.what();
      EXPECT_NE(what.find("jiang.after_break"), std::string::npos) << what;
      if (!bad.empty()) {  // "": Boost's message, which names the key
        EXPECT_NE(what.find("reform | open"), std::string::npos) << what;
      }
    }
  }
}

}  // namespace
}  // namespace rondel
