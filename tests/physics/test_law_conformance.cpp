// The conformance harness: every law of the registry (physics/LawRows.hpp), each test once per law, with the
// law's example parameters (ParamSpec::example, the reference contact of docs/developing.md). A law added to the
// registry is run here without an edit of this file; a law that is exempt from a check declares why
// (LawConcepts.hpp: not_objective, unsplit_work, no_spring). What every law must do:
//  - objectivity: a frame rotated by 37 or 137 degrees changes no force, couple or spring (1e-12), for two discs
//    and at a wall; a rigid spin superposed on the pair (or on the disc and a rotating wall) changes nothing
//    (1e-10) unless the law declares not_objective; an objective law's couple on disc 2 is -M1, so an isolated
//    spinning pair keeps its angular momentum (K7, 1e-10);
//  - the cap: a driven contact's couple (force) never exceeds the law's cap(), and it acts;
//  - its a-priori spring for the critical step bounds the stiffness it shows (docs/physics.md section 4);
//  - stored energy against the ledger: a disc rolling on a wall keeps kinetic + stored energy + the ledger's
//    dissipation (slip, rolling plastic and dashpot work, brittle releases) constant to 1e-3, unless the law
//    declares unsplit_work, on the linear normal law and on walton_braun;
//  - no history committed at the first evaluation (KernelOps::initial, the forces of t = 0);
// and the checkpoint round trip, which needs HDF5: tests/regression/test_law_files.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "K7Pair.hpp"
#include "OneContactRig.hpp"
#include "physics/LawRows.hpp"
#include "physics/PairConstants.hpp"

namespace rondel {
namespace {

using registry::NormalLaws;
using registry::RollingLaws;
using registry::TangentialLaws;

struct LawName {
  template <class L>
  static std::string GetName(int) {
    return L::name;
  }
};

// A check a law declares itself exempt from, with its reason: passed, and said.
void exempt(const char* law, const char* why) { std::printf("[ exempt   ] %s: %s\n", law, why); }

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kR1 = 0.005, kR2 = 0.0075;  // disc D5 and one of 1.5 its radius
constexpr double kDensity = 2650.0;
constexpr double kOverlap = 2e-6;  // F_n = k_n u_n = 2 N at the example k_n

double mass(double R) { return kDensity * std::numbers::pi * R * R; }
double inertia(double R) { return 0.5 * mass(R) * R * R; }
Vec2 rotate(Vec2 a, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * a.x - s * a.y, s * a.x + c * a.y};
}

// The reference contact's parameters with the examples of the normal, tangential and rolling law given.
template <class N, class T, class R>
ContactParams example_params() {
  ContactParams p;
  const LawBlock* blocks[] = {NormalLinear::block, N::block, T::block, R::block};
  for (const LawBlock* block : blocks)
    if (block) p = block->with_examples(p);
  return p;
}

// A contact frozen in one motion: two discs (or a disc and a wall) with their velocities and spins; `frame`
// rotates every vector by an angle, `spin` superposes a rigid rotation Omega about the point c (a wall then
// rotates with it).
struct Motion {
  bool wall = false;
  Vec2 x1{0.013, -0.021}, v1{0.02, -0.01}, v2{-0.01, 0.015};
  double w1 = 7.0, w2 = -3.0;
  double direction = 0.6;  // of the line of centres (the wall's inward normal is its opposite)
};
struct Frame {
  double angle = 0.0, Omega = 0.0;
  Vec2 c{0.004, 0.011};
};

// The kinematics and bodies of the motion in the frame, and the spins the law sees.
struct Seen {
  ContactKinematics k;
  ContactBodies b;
  double w1, w2;
};
Seen seen(const Motion& m, const Frame& f) {
  const Vec2 n = rotate({std::cos(m.direction), std::sin(m.direction)}, f.angle);
  const Vec2 x1 = rotate(m.x1, f.angle);
  Vec2 v1 = rotate(m.v1, f.angle);
  Seen s{};
  s.w1 = m.w1 + f.Omega;
  if (m.wall) {
    const double dist = kR1 - kOverlap;
    const Vec2 p = x1 + wall_lever(kR1, dist) * n;  // the contact point
    v1 += f.Omega * perp(x1 - f.c);
    const Vec2 v_wall = f.Omega * perp(p - f.c);  // at rest, or turning with the frame
    s.w2 = f.Omega;
    s.k = disc_wall_kinematics(n, dist, kR1, v1, v_wall, s.w1, s.w2);
    s.b = disc_wall_bodies(mass(kR1), inertia(kR1));
    return s;
  }
  const double dist = kR1 + kR2 - kOverlap;
  const Vec2 x2 = x1 + dist * n;
  Vec2 v2 = rotate(m.v2, f.angle);
  v1 += f.Omega * perp(x1 - f.c), v2 += f.Omega * perp(x2 - f.c);
  s.w2 = m.w2 + f.Omega;
  s.k = disc_disc_kinematics(x2 - x1, dist, kR1, kR2, v1, v2, s.w1, s.w2);
  s.b = disc_disc_bodies(mass(kR1), mass(kR2), inertia(kR1), inertia(kR2));
  return s;
}

// Every step's force, couples and history of a law run `steps` times on the frozen motion.
struct Trace {
  std::vector<double> values;  // per step: F_n, F_t, M1, M2, then the history slots (tangential, rolling, normal)
  double scale = 0.0;          // the largest |value| of each kind, summed (the tolerance's scale)
  double largest_M1 = 0.0;
};
template <class N, class T, class R>
Trace trace(const ContactParams& p, const Motion& m, const Frame& f, int steps, double dt) {
  const Seen s = seen(m, f);
  std::vector<double> t_slots(T::slots.size() + 1, 0.0), r_slots(R::slots.size() + 1, 0.0),
      n_slots(N::slots.size() + 1, 0.0);
  std::vector<double*> t_cols, r_cols, n_cols;
  for (double& v : t_slots) t_cols.push_back(&v);
  for (double& v : r_slots) r_cols.push_back(&v);
  for (double& v : n_slots) n_cols.push_back(&v);
  const auto th = history_row<typename T::History, T::slots.size()>(t_cols.data(), 0);
  const auto rh = history_row<typename R::History, R::slots.size()>(r_cols.data(), 0);
  const auto nh = history_row<typename N::History, N::slots.size()>(n_cols.data(), 0);
  Trace out;
  double M1_prev = 0.0, max_F = 0.0, max_M = 0.0;
  for (int n = 0; n < steps; ++n) {
    const double F_n = N::force(ContactInput{p, s.b, s.k}, nh).F_n;
    const ContactInput in{p, s.b, s.k, F_n, dt, s.w1, s.w2, M1_prev};
    const TangentialForce F_t = T::force(in, th);
    const RollingCouple M =
        R::moment(N::kStiffening ? ContactInput{N::linearised(in), s.b, s.k, F_n, dt, s.w1, s.w2, M1_prev} : in, rh);
    M1_prev = M.M1;
    for (double v : {F_n, F_t.F_t, M.M1, M.M2}) out.values.push_back(v);
    for (std::size_t k = 0; k < T::slots.size(); ++k) out.values.push_back(t_slots[k]);
    for (std::size_t k = 0; k < R::slots.size(); ++k) out.values.push_back(r_slots[k]);
    for (std::size_t k = 0; k < N::slots.size(); ++k) out.values.push_back(n_slots[k]);
    max_F = std::max({max_F, std::fabs(F_n), std::fabs(F_t.F_t)});
    max_M = std::max({max_M, std::fabs(M.M1), std::fabs(M.M2)});
    out.largest_M1 = std::max(out.largest_M1, std::fabs(M.M1));
  }
  out.scale = max_F + max_M;
  return out;
}

// "" when the traces agree within tol x their scale (plus the history's own scale), else the first difference.
std::string differ(const Trace& a, const Trace& b, double tol) {
  if (a.values.size() != b.values.size()) return "different lengths";
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    const double scale = std::max({a.scale, std::fabs(a.values[i]), 1e-300});
    if (std::fabs(a.values[i] - b.values[i]) > tol * scale)
      return "value " + std::to_string(i % 8) + " of step " + std::to_string(i / 8) + ": " +
             std::to_string(a.values[i]) + " against " + std::to_string(b.values[i]);
  }
  return "";
}

// ------------------------------------------------------------------------------------------ rolling laws

template <class R>
class RollingConformance : public ::testing::Test {};
TYPED_TEST_SUITE(RollingConformance, RollingLaws::types<::testing::Types>, LawName);

TYPED_TEST(RollingConformance, ARotatedFrameChangesNothing) {
  using R = TypeParam;
  const ContactParams p = example_params<NormalLinear, TangentialCoulomb, R>();
  for (const bool wall : {false, true}) {
    Motion m;
    m.wall = wall;
    const Trace base = trace<NormalLinear, TangentialCoulomb, R>(p, m, {}, 300, 1e-5);
    for (const double angle : {37.0, 137.0}) {
      SCOPED_TRACE(std::string(wall ? "at a wall, " : "two discs, ") + std::to_string(angle) + " degrees");
      const Trace turned = trace<NormalLinear, TangentialCoulomb, R>(p, m, {angle * kDeg}, 300, 1e-5);
      EXPECT_EQ(differ(base, turned, 1e-12), "");
    }
  }
}

TYPED_TEST(RollingConformance, ASuperposedRigidSpinChangesNothingUnlessNotObjective) {
  using R = TypeParam;
  if constexpr (!objective<R>()) {
    exempt(R::name, R::not_objective);
  } else {
    const ContactParams p = example_params<NormalLinear, TangentialCoulomb, R>();
    for (const bool wall : {false, true}) {
      SCOPED_TRACE(wall ? "a disc and a wall turning with it" : "two discs");
      Motion m;
      m.wall = wall;
      const Trace base = trace<NormalLinear, TangentialCoulomb, R>(p, m, {}, 300, 1e-5);
      const Trace spun = trace<NormalLinear, TangentialCoulomb, R>(p, m, {0.0, 5.0}, 300, 1e-5);
      EXPECT_EQ(differ(base, spun, 1e-10), "");
    }
  }
}

// K7 (docs/validation.md section 1): M2 = -M1, so an isolated pair in rigid spin with a relative spin on top keeps
// its angular momentum (1e-10 relative), whatever the couple does (springs load, caps are reached, brittle
// contacts break).
TYPED_TEST(RollingConformance, AnObjectiveLawKeepsTheAngularMomentumOfAnIsolatedPair) {
  using R = TypeParam;
  if constexpr (!objective<R>()) {
    exempt(R::name, R::not_objective);
  } else {
    ContactParams p = testing_rig::k7_params();
    if (const LawBlock* block = R::block) p = block->with_examples(p);
    const testing_rig::K7Result r = testing_rig::run_k7<R>(p, 5.0, 2.0, -1.0, 1.0, 1e-4);
    EXPECT_TRUE(r.in_contact);
    EXPECT_LE(r.max_dev, 1e-10 * std::fabs(r.L0));
    if constexpr (R::kActive) {
      EXPECT_GT(r.max_M, 0.0) << "the couple acted";
    }
  }
}

TYPED_TEST(RollingConformance, TheCoupleNeverExceedsTheCapAndActs) {
  using R = TypeParam;
  const ContactParams p = example_params<NormalLinear, TangentialCoulomb, R>();
  for (const bool wall : {false, true}) {
    SCOPED_TRACE(wall ? "at a wall" : "two discs");
    Motion m;
    m.wall = wall, m.w1 = 20.0, m.w2 = -10.0;  // drives every spring to its cap within a few dozen steps
    const Seen s = seen(m, {});
    const double F_n = NormalLinear::force(ContactInput{p, s.b, s.k}).F_n;
    const double cap = R::cap(ContactInput{p, s.b, s.k, F_n});
    const Trace t = trace<NormalLinear, TangentialCoulomb, R>(p, m, {}, 400, 1e-5);
    EXPECT_LE(t.largest_M1, cap * (1.0 + 1e-12)) << "cap " << cap;
    if constexpr (R::kActive) {
      EXPECT_GT(t.largest_M1, 0.0) << "the couple acts";
    }
    for (std::size_t i = 0; i + 3 < t.values.size(); i += 4 + TangentialCoulomb::slots.size() + R::slots.size()) {
      const double M1 = t.values[i + 2], M2 = t.values[i + 3];
      if constexpr (!own_couples<R>()) {
        ASSERT_EQ(M2, -M1) << "step " << i;
      }
    }
  }
}

// docs/physics.md section 4: the critical step takes the law's spring; the couple of one step from a fresh
// history, M = -(K theta + C thetadot) for a spring-dashpot, must not be stiffer than it.
TYPED_TEST(RollingConformance, ItsSpringBoundsTheStiffnessItShows) {
  using R = TypeParam;
  if constexpr (!RollingAPrioriSpring<R>) {
    exempt(R::name, R::no_spring);
  } else {
    const ContactParams p = example_params<NormalLinear, TangentialCoulomb, R>();
    for (const bool wall : {false, true}) {
      SCOPED_TRACE(wall ? "at a wall" : "two discs");
      // A small rolling without slip, far below every cap (alonso_marroquin answers pure rolling only).
      Motion m;
      m.wall = wall, m.v1 = {}, m.v2 = {}, m.w1 = 0.1, m.w2 = -0.1 * kR1 / kR2;
      if (wall)
        m.w2 = 0.0,
        m.v1 = -0.1 * wall_lever(kR1, kR1 - kOverlap) * perp(Vec2{std::cos(m.direction), std::sin(m.direction)});
      const double dt = 1e-5;
      const Seen s = seen(m, {});
      const RollingSpring spring = R::spring(ContactInput{p, s.b, s.k});
      const Trace t = trace<NormalLinear, TangentialCoulomb, R>(p, m, {}, 1, dt);
      const double M1 = t.values[2], rate = std::fabs(s.k.thetadot_r);
      EXPECT_GT(std::fabs(M1), 0.0) << "a spring law answers a rotation";
      EXPECT_LE(std::fabs(M1), (spring.K * dt + spring.C) * rate * (1.0 + 1e-9))
          << "K " << spring.K << ", C " << spring.C << ": the law is stiffer than the spring the critical step takes";
    }
  }
}

// KernelOps::initial (the forces of t = 0, docs/design.md section 4): whatever the laws do with the history,
// none of it is committed.
TYPED_TEST(RollingConformance, TheFirstEvaluationCommitsNoHistory) {
  using R = TypeParam;
  const ContactParams p = example_params<NormalLinear, TangentialCoulomb, R>();
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  for (const double R2 : {kR2, static_cast<double>(INFINITY)}) {
    testing_rig::OneContactRig rig({"linear", "coulomb", R::name}, p, kR1, R2, kOverlap, p.k_n * kOverlap);
    ContactTable& rows = rig.row_table();
    std::vector<std::uint64_t> before;
    for (std::size_t s = 0; s < rows.slot.size(); ++s) rows.slot[s][0] = 1e-7 * static_cast<double>(s + 1);
    for (const auto& slot : rows.slot) before.push_back(bits(slot[0]));
    rig.discs().velocity[0] = 2.0 * rig.t;
    rig.discs().omega[0] = 300.0;
    rig.start(1e-5);
    for (std::size_t s = 0; s < rows.slot.size(); ++s)
      EXPECT_EQ(bits(rows.slot[s][0]), before[s]) << "slot " << s << " committed, R2 = " << R2;
  }
}

// The rolling couple's work as the ledger books it (W_rolling, from the kernel's trapezoid) against what the law
// stores (the kernel's stored-energy pass) and dissipates (rolling plastic and dashpot work, brittle releases):
// -W_r - (E_r(t) - E_r(0)) - D_r, relative to the rolling work done, for a disc on a wall pressed by a preload.
struct LedgerGap {
  double gap = 0.0, work = 0.0, yielded = 0.0;
};
template <class R>
LedgerGap rolling_ledger(double omega, double slip, int steps, const char* normal = "linear") {
  ContactParams p = example_params<NormalLinear, TangentialCoulomb, R>();
  registry::NormalLaws::with(normal, [&]<class N>() {
    ContactParamTable table(1);  // the normal law's examples, with what the set-up derives from them (K2)
    table.pair(0, 0) = N::block->with_examples(p);
    resolve_pair_constants(table, {Material{}});
    p = table.pair(0, 0);
  });
  testing_rig::OneContactRig rig({normal, "coulomb", R::name}, p, kR1, INFINITY, kOverlap, p.k_n * kOverlap);
  rig.discs().omega[0] = omega;
  rig.discs().velocity[0] = -(1.0 - slip) * omega * wall_lever(kR1, kR1 - kOverlap) * rig.t;
  rig.start(1e-5);
  const double E0 = rig.summary().rolling;
  double W = 0.0, D = 0.0;
  LedgerGap out;
  for (int s = 0; s < steps; ++s) {
    LedgerStep step;
    rig.step(&step);
    W += step.W_r, out.work += std::fabs(step.W_r);
    D += step.D_r_plastic + step.D_r_dashpot + step.E_r_break;
    out.yielded += step.D_r_plastic + step.E_r_break;
  }
  out.gap = std::fabs(-W - (rig.summary().rolling - E0) - D) / std::max(out.work, 1e-300);
  return out;
}

// Rolling without slip below the cap, the couple's spring loaded and unloaded over a few periods of the rolling
// mode: the stored energy (and the dashpot) must carry the work to 1e-5 of it; then rolling and slipping hard, the
// couple at its cap (or broken): the dissipation must carry it to 1e-3 (the step in which a spring-slider first yields
// is booked to first order).
TYPED_TEST(RollingConformance, ItsStoredEnergyAndDissipationCloseTheLedger) {
  using R = TypeParam;
  if constexpr (!R::kActive || !splits_work<R>()) {
    if constexpr (R::kActive) exempt(R::name, R::unsplit_work);
  } else {
    const LedgerGap elastic = rolling_ledger<R>(0.2, 0.0, 3000);
    EXPECT_LE(elastic.gap, 1e-5) << "below the cap (work " << elastic.work << " J)";
    EXPECT_EQ(elastic.yielded, 0.0) << "the elastic run stays below the cap";
    EXPECT_GT(elastic.work, 0.0) << "the rolling couple acted";
    const LedgerGap plastic = rolling_ledger<R>(80.0, 0.25, 3000);
    EXPECT_LE(plastic.gap, 1e-3) << "at the cap (work " << plastic.work << " J)";
    EXPECT_GT(plastic.yielded, 0.0) << "the couple yielded or broke";
    // The same on walton_braun (its K1 the rolling laws' k_n; the preload holds the disc on its loading line).
    const LedgerGap wb = rolling_ledger<R>(80.0, 0.25, 3000, "walton_braun");
    EXPECT_LE(wb.gap, 1e-3) << "at the cap on walton_braun (work " << wb.work << " J)";
    EXPECT_GT(wb.yielded, 0.0) << "the couple yielded or broke on walton_braun";
  }
}

// ------------------------------------------------------------------------------------------ tangential laws

template <class T>
class TangentialConformance : public ::testing::Test {};
TYPED_TEST_SUITE(TangentialConformance, TangentialLaws::types<::testing::Types>, LawName);

// The normal law a tangential law runs with: the one it needs (mindlin: hertz), else linear.
template <class T, class F>
void with_its_normal(F&& f) {
  if constexpr (needed_normal<T>() != nullptr)
    NormalLaws::with(needed_normal<T>(), [&]<class N>() { f.template operator()<N>(); });
  else
    f.template operator()<NormalLinear>();
}

// The example parameters with the constants the set-up derives from them (resolve_pair_constants: an elastic
// normal law's pair constants, glass on glass; walton_braun's K2).
template <class N, class T>
ContactParams tangential_params() {
  Material glass;
  glass.name = "glass", glass.youngs_modulus = 7e10, glass.poisson_ratio = 0.25;
  ContactParamTable table(1);
  table.pair(0, 0) = example_params<N, T, RollingNone>();
  resolve_pair_constants(table, {glass});
  return table.pair(0, 0);
}

TYPED_TEST(TangentialConformance, ARotatedFrameOrASuperposedSpinChangesNothing) {
  using T = TypeParam;
  with_its_normal<T>([&]<class N>() {
    const ContactParams p = tangential_params<N, T>();
    for (const bool wall : {false, true}) {
      Motion m;
      m.wall = wall;
      const Trace base = trace<N, T, RollingNone>(p, m, {}, 300, 1e-5);
      for (const double angle : {37.0, 137.0})
        EXPECT_EQ(differ(base, trace<N, T, RollingNone>(p, m, {angle * kDeg}, 300, 1e-5), 1e-12), "")
            << angle << " degrees, wall " << wall;
      EXPECT_EQ(differ(base, trace<N, T, RollingNone>(p, m, {0.0, 5.0}, 300, 1e-5), 1e-10), "")
          << "spin, wall " << wall;
    }
  });
}

TYPED_TEST(TangentialConformance, TheForceNeverExceedsMuFn) {
  using T = TypeParam;
  with_its_normal<T>([&]<class N>() {
    const ContactParams p = tangential_params<N, T>();
    Motion m;
    m.v1 = {0.5, -0.3};  // slides hard
    const double F_n = trace<N, T, RollingNone>(p, m, {}, 1, 1e-5).values[0];
    const Trace t = trace<N, T, RollingNone>(p, m, {}, 400, 1e-5);
    for (std::size_t i = 0; i + 1 < t.values.size(); i += 4 + T::slots.size() + N::slots.size())
      ASSERT_LE(std::fabs(t.values[i + 1]), p.mu * F_n * (1.0 + 1e-12)) << "step " << i;
  });
}

// ------------------------------------------------------------------------------------------ normal laws

template <class N>
class NormalConformance : public ::testing::Test {};
TYPED_TEST_SUITE(NormalConformance, NormalLaws::types<::testing::Types>, LawName);

TYPED_TEST(NormalConformance, NoTensionAndAFrameFreeForce) {
  using N = TypeParam;
  const ContactParams p = tangential_params<N, TangentialNone>();
  Motion m;
  m.v1 = {-3.0, -2.0};  // the discs part fast: a dashpot would pull
  const Trace base = trace<N, TangentialNone, RollingNone>(p, m, {}, 3, 1e-5);
  for (std::size_t i = 0; i < base.values.size(); i += 4 + N::slots.size())
    EXPECT_GE(base.values[i], 0.0) << "no tension";
  EXPECT_EQ(differ(base, trace<N, TangentialNone, RollingNone>(p, m, {37.0 * kDeg, 5.0}, 3, 1e-5), 1e-10), "");
  const Seen s = seen(Motion{}, {});
  std::vector<double> fresh(N::slots.size() + 1, 0.0);  // a new contact's history
  std::vector<double*> columns;
  for (double& v : fresh) columns.push_back(&v);
  EXPECT_GT(N::stored(ContactInput{p, s.b, s.k}, history_row<typename N::History, N::slots.size()>(columns.data(), 0)),
            0.0)
      << "an overlapping contact stores energy";
}

}  // namespace
}  // namespace rondel
