// Rotating walls, docs/validation.md section 11 (docs/physics.md section 8), through the library's own fused
// kernel (select_kernel) with one disc and one wall row:
//  R1: a disc carried by a segment that rotates at Omega about a fixed centre c, in rigid co-rotation
//      (v1 = Omega z x (x1 - c), omega1 = Omega, the disc turned with the segment every step): zero sliding
//      velocity, zero relative rotation, and for every rolling law no couple and no tangential force (to
//      round-off) over 2,000 steps; the segment's ends after N steps are the exact rotation by N Omega dt.
//  R2: the same disc with omega1 = 0: V_r = -R1 Omega and V_s = -a1 Omega; `wang`'s first couple is
//      R1 k_r R1 Omega dt (below its cap), of the sign that resists the relative rotation.
//  R3: a disc inside a circle wall rotating at Omega, gravity off, pressed to the rim by a constant radial
//      force P (outwards from c): friction drags it along, the disc rolls inside the drum until the `wang`
//      rolling couple has stopped the relative rotation, and it ends in rigid co-rotation (omega1 = Omega,
//      v1 = Omega z x (x1 - c)) with the rolling couple and the tangential force gone to round-off; the
//      kinetic energy is that of the rigid co-rotation, and the ledger closes: W_walls + W_P + W_contacts =
//      KE gained (W_P the radial force's work), so W_walls = KE gained + the contacts' dissipation and
//      stored energy, to the trapezoid's integration error (below 1e-3 of W_walls, halved with dt).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ForceAssembly.hpp"
#include "core/Integrator.hpp"
#include "core/Vec2.hpp"
#include "core/Wall.hpp"
#include "physics/ContactKernel.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawRegistry.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

constexpr double kR = test::d5::R;
constexpr double kDensity = test::d5::density;

// Parameters for every rolling law at once (each law reads its own fields): every law's examples, then these
// values, with every dashpot on.
ContactParams all_law_params() {
  ContactParams p = test::set_S();
  for (const LawInfo& law : law_catalog().rolling.laws)
    if (law.block) p = law.block->with_examples(p);
  p.zeta_n = 0.3;
  p.zeta_t = 0.5;
  p.delta = 0.3;
  p.k_r = 3e4;
  p.c_r = 20.0;
  p.mu_r = 0.1;
  p.K_r = 0.75;
  p.C_r = 1e-4;
  p.eta = 1e-3;
  p.f_lim = 0.08;
  p.theta_rmax = 0.035;
  p.nu = 0.3;
  p.f_visc = 0.5;
  return p;
}

// Every rolling law of the registry.
std::vector<std::string> rolling_laws() {
  std::vector<std::string> laws;
  for (const LawInfo& law : law_catalog().rolling.laws) laws.emplace_back(law.keyword);
  return laws;
}

Vec2 rotate(Vec2 r, double c, double s) { return {c * r.x - s * r.y, s * r.x + c * r.y}; }

// One disc (gid 1) and one wall with its row, and the kernel of the selected laws.
struct OneWallRow {
  LawSelection laws;
  ContactParamTable params{1};
  KernelOps ops;
  ContactTable pairs, rows;
  DiscStore discs;
  WallSet walls;
  Domain domain{-10.0, 10.0, -10.0, 10.0, false, false};
  ForceAssembly assembly;

  OneWallRow(const std::string& rolling, const ContactParams& p, const Wall& w, Vec2 x1)
      : laws{"linear", "coulomb", rolling} {
    params.pair(0, 0) = p;
    params.wall(0) = p;
    ops = select_kernel(laws);
    pairs = make_contact_table(laws, false);
    rows = make_contact_table(laws, true);
    discs.add(1, 0, kR, kDensity, 1.0, x1);
    walls.push_back(w);
    rows.push(ContactKey{1, 0}, 0, 0, 0);
    assembly.build(discs);
  }
  KernelContext context(double dt) { return KernelContext{discs, domain, walls, params, dt}; }
  // The kernel once at the discs' present state (forces and torques into the discs' sums).
  LedgerStep evaluate(double dt) {
    ForceAssembly::begin(discs, BodyForce{});
    LedgerStep L;
    ops.run(context(dt), pairs, rows, ForceSums::of(discs), L);
    assembly.finish(discs);
    return L;
  }
  double M1() const { return rows.M1.empty() ? 0.0 : rows.M1[0]; }
};

// The rotating segment of R1 and R2: from (-0.05, 0) to (0.05, 0), discs above it, turning about
// c = (0.02, -0.03) at Omega = 5 rad/s; the disc at x = 0.01 with the overlap u0.
constexpr double kOmega = 5.0, kU0 = 2e-6, kDtR = 1e-5;
const Vec2 kCentre{0.02, -0.03};
Wall rotating_segment() {
  Wall w;
  w.kind = Wall::Kind::segment;
  w.p0 = {-0.05, 0.0};
  w.p1 = {0.05, 0.0};
  w.centre = kCentre;
  w.omega = kOmega;
  w.lever =
      std::max(std::hypot(w.p0.x - kCentre.x, w.p0.y - kCentre.y), std::hypot(w.p1.x - kCentre.x, w.p1.y - kCentre.y));
  return w;
}

TEST(RotatingWall, RigidCoRotationOnASegmentHasNoSlipAndNoCoupleForEveryLaw) {
  const ContactParams p = all_law_params();
  const int steps = 2000;
  for (const std::string& law : rolling_laws()) {
    SCOPED_TRACE("rolling = " + law);
    OneWallRow rig(law, p, rotating_segment(), {0.01, kR - kU0});
    const double c = std::cos(kOmega * kDtR), s = std::sin(kOmega * kDtR);
    double max_Vs = 0.0, max_Ft = 0.0, max_M = 0.0, min_Fn = INFINITY;
    for (int k = 0; k < steps; ++k) {
      Wall& w = rig.walls[0];
      w.move(kDtR);
      Vec2& x1 = rig.discs.position[0];
      x1 = kCentre + rotate(x1 - kCentre, c, s);
      rig.discs.velocity[0] = kOmega * perp(x1 - kCentre);
      rig.discs.omega[0] = kOmega;
      const Wall::Proximity prox = w.proximity(x1);
      const Vec2 v_w = w.surface_velocity(x1 + wall_lever(kR, prox.dist) * prox.n);
      const ContactKinematics kin =
          disc_wall_kinematics(prox.n, prox.dist, kR, rig.discs.velocity[0], v_w, kOmega, kOmega);
      EXPECT_EQ(kin.thetadot_r, 0.0);
      EXPECT_EQ(kin.V_r, 0.0);
      max_Vs = std::max(max_Vs, std::fabs(kin.V_s));
      rig.evaluate(kDtR);
      max_Ft = std::max(max_Ft, std::fabs(rig.rows.F_t[0]));
      max_M = std::max(max_M, std::fabs(rig.M1()));
      min_Fn = std::min(min_Fn, rig.rows.F_n[0]);
    }
    const double U = kOmega * 0.05;  // a surface speed of the set-up
    EXPECT_LE(max_Vs, 1e-13 * U);
    EXPECT_GT(min_Fn, 0.5 * p.k_n * kU0);  // the contact stayed closed
    EXPECT_LE(max_Ft, 1e-9 * p.mu * min_Fn);
    EXPECT_EQ(max_M, 0.0);  // thetadot_r = 0 exactly: every law's couple is exactly 0
    // The ends after the steps: the exact rotation by steps x Omega dt about c (the incremental rotation
    // drifts by round-off only), and the angle is their sum.
    const double turned = steps * kOmega * kDtR;
    const Vec2 exact0 = kCentre + rotate(Vec2{-0.05, 0.0} - kCentre, std::cos(turned), std::sin(turned));
    const Vec2 exact1 = kCentre + rotate(Vec2{0.05, 0.0} - kCentre, std::cos(turned), std::sin(turned));
    EXPECT_NEAR(rig.walls[0].p0.x, exact0.x, 1e-13);
    EXPECT_NEAR(rig.walls[0].p0.y, exact0.y, 1e-13);
    EXPECT_NEAR(rig.walls[0].p1.x, exact1.x, 1e-13);
    EXPECT_NEAR(rig.walls[0].p1.y, exact1.y, 1e-13);
    EXPECT_NEAR(rig.walls[0].angle, turned, 1e-12 * turned);
    // The neighbour list's bound on the wall's motion covers the farthest end's arc.
    EXPECT_GE(rig.walls[0].moved_since_build(), turned * std::hypot(0.05 + kCentre.x, kCentre.y) * (1.0 - 1e-12));
  }
}

TEST(RotatingWall, ADiscWithoutSpinSeesVrMinusR1OmegaForWang) {
  ContactParams p = all_law_params();
  p.c_r = 0.0;
  OneWallRow rig("wang", p, rotating_segment(), {0.01, kR - kU0});
  Vec2 x1 = rig.discs.position[0];
  rig.discs.velocity[0] = kOmega * perp(x1 - kCentre);  // carried by the wall, not spinning
  rig.discs.omega[0] = 0.0;
  const Wall& w = rig.walls[0];
  const Wall::Proximity prox = w.proximity(x1);
  const double a1 = wall_lever(kR, prox.dist);
  const ContactKinematics kin = disc_wall_kinematics(prox.n, prox.dist, kR, rig.discs.velocity[0],
                                                     w.surface_velocity(x1 + a1 * prox.n), 0.0, w.omega);
  EXPECT_DOUBLE_EQ(kin.V_r, -kR * kOmega);
  EXPECT_DOUBLE_EQ(kin.thetadot_r, -kOmega);
  EXPECT_NEAR(kin.V_s, -a1 * kOmega, 1e-13 * kOmega * kR);
  // One kernel step: x_r = V_r dt, M = R* k_r R1 Omega dt (below the cap mu_r F_n R1), positive: it resists
  // the disc's rotation relative to the wall (-Omega).
  rig.evaluate(kDtR);
  const double expected = kR * p.k_r * kR * kOmega * kDtR;
  ASSERT_LT(expected, p.mu_r * rig.rows.F_n[0] * kR);
  EXPECT_NEAR(rig.M1(), expected, 1e-9 * expected);
  EXPECT_GT(rig.M1(), 0.0);
}

// The drum case of R3 at the step dt for 1.5 s: the state at the end and the ledger.
struct DrumRun {
  double m = 0.0, I = 0.0, mu = 0.0, mu_r = 0.0, P = 0.0, Omega = 0.0, R_c = 0.0;
  Vec2 x, v;
  double omega1 = 0.0, max_rel_spin = 0.0, F_n = 0.0, F_t = 0.0, M = 0.0;
  double KE0 = 0.0, KE = 0.0, stored0 = 0.0, stored = 0.0, W_w = 0.0, W_c = 0.0, W_P = 0.0, D_slip = 0.0;
  double residual() const { return (KE - KE0) - (W_w + W_P + W_c); }
};

DrumRun run_drum(double dt) {
  // D5 in a drum of R_c = 0.05 m turning at Omega = 2 rad/s (rim speed 0.1 m/s), gravity off, P = 2 N.
  DrumRun out;
  const double R_c = 0.05, Omega = 2.0, P = 2.0;
  ContactParams p = test::set_S();
  p.zeta_n = 0.3, p.zeta_t = 0.5;
  p.k_r = 3e4, p.mu_r = 0.1, p.c_r = 50.0;  // wang, with a rolling dashpot
  Wall drum;
  drum.kind = Wall::Kind::circle;
  drum.centre = drum.p0 = {0.0, 0.0};
  drum.radius = R_c;
  drum.omega = Omega;
  const double u0 = P / p.k_n;
  OneWallRow rig("wang", p, drum, {R_c - kR + u0, 0.0});  // at rest, on the rim, at the static overlap
  DiscStore& D = rig.discs;
  out.m = D.mass[0], out.I = D.inertia[0], out.mu = p.mu, out.mu_r = p.mu_r, out.P = P, out.Omega = Omega;
  out.R_c = R_c;
  auto radial = [&](Vec2 x) { return (P / std::sqrt(dot(x - drum.centre, x - drum.centre))) * (x - drum.centre); };
  auto kinetic = [&] {
    return 0.5 * out.m * dot(D.velocity[0], D.velocity[0]) + 0.5 * out.I * D.omega[0] * D.omega[0];
  };
  // Forces at t = 0, as Simulation starts: no history committed.
  ForceAssembly::begin(D, BodyForce{});
  rig.ops.initial(rig.context(0.0), rig.pairs, rig.rows, ForceSums::of(D));
  rig.assembly.finish(D);
  D.force[0] += radial(D.position[0]);
  out.KE0 = kinetic();
  out.stored0 = rig.ops.stored(rig.context(dt), rig.pairs, rig.rows).total();
  Vec2 f_P_last = radial(D.position[0]);
  const auto steps = static_cast<long>(std::llround(1.5 / dt));
  for (long k = 0; k < steps; ++k) {
    Integrator::half_kick_drift(D, rig.domain, dt, BodyForce{}, false);
    rig.walls[0].move(dt);
    rig.assembly.begin_fixed_and_ghosts(D);
    LedgerStep L;
    rig.ops.run(rig.context(dt), rig.pairs, rig.rows, ForceSums::of(D), L);
    rig.assembly.finish(D);
    const Vec2 f_P = radial(D.position[0]);
    D.force[0] += f_P;
    out.W_P += 0.5 * dt * dot(f_P_last + f_P, D.velocity[0]);  // the half-step velocity, as the kernel's works
    f_P_last = f_P;
    Integrator::half_kick(D, dt);
    out.W_w += L.W_w, out.W_c += L.W_n + L.W_t + L.W_r, out.D_slip += L.D_slip;
    out.max_rel_spin = std::max(out.max_rel_spin, std::fabs(D.omega[0] - Omega));
  }
  out.x = D.position[0], out.v = D.velocity[0], out.omega1 = D.omega[0];
  out.F_n = rig.rows.F_n[0], out.F_t = rig.rows.F_t[0], out.M = rig.M1();
  out.KE = kinetic();
  out.stored = rig.ops.stored(rig.context(dt), rig.pairs, rig.rows).total();
  return out;
}

TEST(RotatingWall, DiscInARotatingDrumReachesRigidCoRotationAndTheLedgerCloses) {
  const DrumRun r = run_drum(1e-5);
  const double Omega = r.Omega, U = Omega * r.R_c;
  const Vec2 v_rigid = Omega * perp(r.x);  // the drum's centre is the origin
  // It rolled inside the drum on the way (omega1 far from Omega), then co-rotates rigidly.
  EXPECT_GT(r.max_rel_spin, 2.0 * Omega);
  EXPECT_NEAR(r.omega1, Omega, 1e-9 * Omega);
  EXPECT_NEAR(r.v.x, v_rigid.x, 1e-9 * U);
  EXPECT_NEAR(r.v.y, v_rigid.y, 1e-9 * U);
  EXPECT_NEAR(r.F_n, r.P + r.m * Omega * Omega * std::sqrt(dot(r.x, r.x)), 1e-6 * r.P);  // radial balance
  EXPECT_LE(std::fabs(r.F_t), 1e-9 * r.mu * r.F_n);
  EXPECT_LE(std::fabs(r.M), 1e-9 * r.mu_r * r.F_n * kR);
  // Energy: the rigid co-rotation's kinetic energy; the wall gave more than the disc gained, the rest was
  // dissipated (Coulomb slip, dashpots).
  const double KE_rigid = 0.5 * r.m * dot(v_rigid, v_rigid) + 0.5 * r.I * Omega * Omega;
  EXPECT_NEAR(r.KE, KE_rigid, 1e-9 * KE_rigid);
  const double dissipated = -r.W_c - (r.stored - r.stored0);
  EXPECT_GT(r.W_w, r.KE - r.KE0);
  EXPECT_GT(dissipated, 0.1 * r.W_w);
  EXPECT_GT(r.D_slip, 0.0);
  // The ledger closes, W_walls + W_P = KE gained + stored + dissipated (KE - KE0 = W_w + W_P + W_c), to the
  // integration error of the trapezoid (docs/physics.md section 5: the last step's force is booked along this
  // step's n and t, which turn with the disc's orbit): below 1e-3 of W_walls, and halved with the step.
  std::printf("[ drum     ] dt 1e-5: W_walls %.9e J, KE gained %.9e J, dissipated %.9e J, residual %.3e\n", r.W_w,
              r.KE - r.KE0, dissipated, r.residual());
  EXPECT_LE(std::fabs(r.residual()), 1e-3 * r.W_w);
  const DrumRun half = run_drum(5e-6);
  std::printf("[ drum     ] dt 5e-6: residual %.3e\n", half.residual());
  EXPECT_LE(std::fabs(half.residual()), 0.6 * std::fabs(r.residual()));
  EXPECT_NEAR(half.KE, r.KE, 1e-6 * r.KE);  // the same end state
}

}  // namespace
}  // namespace rondel
