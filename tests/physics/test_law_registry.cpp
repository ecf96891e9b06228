// The law registry (physics/LawRegistry): every row is a complete law (the concepts), keywords are unique,
// declared defaults lie in their declared ranges, the critical step sees each law's a-priori rolling spring
// as docs/physics.md section 4 writes it, and the resolved configuration holds exactly the selected law's block.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "OneContactRig.hpp"
#include "core/Config.hpp"
#include "core/Errors.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "physics/LawConcepts.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/RollingWang.hpp"

namespace rondel {
namespace {

// A rolling law without its cap: the concept refuses it (the registry's static_assert would fail).
struct RollingWithoutCap {
  static constexpr const char* name = "without_cap";
  static constexpr const LawBlock* block = nullptr;
  static constexpr bool kActive = true;
  static constexpr std::array<const char*, 0> slots{};
  struct History {};
  static constexpr const char* no_spring = "test";
  static RollingCouple moment(const ContactInput&, History) { return {}; }
  static double stored(const ContactInput&, History) { return 0.0; }
};
static_assert(RollingLawType<RollingWang>);
static_assert(!RollingLawType<RollingWithoutCap>, "a law without cap() must not satisfy the concept");

TEST(LawRegistry, KeywordsAreUniqueWithinEachKind) {
  for (const LawKind* kind : law_catalog().kinds()) {
    SCOPED_TRACE(kind->kind);
    ASSERT_FALSE(kind->laws.empty());
    std::set<std::string> seen;
    for (const LawInfo& law : kind->laws) EXPECT_TRUE(seen.insert(law.keyword).second) << law.keyword << " twice";
  }
}

TEST(LawRegistry, BlockSectionsAndKeysAreUnique) {
  std::set<std::string> sections, keys;
  for (const LawBlock* block : law_catalog().blocks()) {
    EXPECT_TRUE(sections.insert(block->section).second) << block->section;
    EXPECT_FALSE(block->params.empty()) << block->section << " declares no parameter";
    for (const ParamSpec& p : block->params)
      EXPECT_TRUE(keys.insert(std::string(block->section) + "." + p.key).second) << block->section << "." << p.key;
  }
}

TEST(LawRegistry, EveryDefaultLiesInItsRange) {
  for (const LawBlock* block : law_catalog().blocks())
    for (const ParamSpec& p : block->params) {
      if (p.presence != Presence::defaulted) continue;
      EXPECT_TRUE(p.range.contains(p.def))
          << block->section << "." << p.key << " = " << p.def << " is outside " << p.range.text();
    }
}

TEST(LawRegistry, UnknownKeywordIsAConfigErrorNamingTheKey) {
  LawSelection laws;
  laws.rolling = "bogus";
  try {
    select_kernel(laws);
    ADD_FAILURE() << "accepted contact.rolling = bogus";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("contact.rolling"), std::string::npos) << e.what();
  }
}

// docs/physics.md section 4 for two equal discs, tangential law none: the rolling mode has
// omega^2 = K/I_red, zeta = C/(2 sqrt(K I_red)), with K and C as docs/physics.md section 3 gives them, for the laws
// of the table (a law outside it is held to the bound of the conformance tests: its spring is not softer than
// the law).
TEST(LawRegistry, RollingSpringGivesTheCriticalStepOfPhysicsSection4) {
  const double R = 0.01, m = 2650.0 * std::numbers::pi * R * R, I = 0.5 * m * R * R;
  ContactParams p;
  p.k_n = 1e4;
  p.zeta_n = 0.1;
  p.delta = 3.0;  // B = delta r: the rolling mode is stiffer than the normal one
  p.k_r = 1e6;
  p.c_r = 1.0;
  p.K_r = 5.0;
  p.C_r = 0.01;
  const double I_red = I * I / (I + I), m_eff = 0.5 * m, r = R;  // r = 2 R1 R2/(R1 + R2)
  const double c_n = 2.0 * p.zeta_n * std::sqrt(m_eff * p.k_n), B = p.delta * r, R_star = 0.5 * R;
  const std::map<std::string, RollingSpring> formula = {
      {"jiang_plastic", {p.k_n * B * B / 12.0, c_n * B * B / 12.0}},
      {"jiang_brittle", {p.k_n * B * B / 12.0, c_n * B * B / 12.0}},
      {"wang", {p.k_r * R_star * R_star, p.c_r * R_star * R_star}},
      {"alonso_marroquin", {p.k_r * R_star * R_star, p.c_r * R_star * R_star}},
      {"iwashita_oda", {p.K_r, p.C_r}}};
  int with_spring = 0;
  for (const LawInfo& law : law_catalog().rolling.laws) {
    SCOPED_TRACE(law.keyword);
    const LawSelection laws{"linear", "none", law.keyword};
    const auto spring = rolling_spring(laws, p, disc_disc_bodies(m, m, I, I), contact_geometry(R, R, false));
    if (!spring) continue;
    ++with_spring;
    const auto expected = formula.find(law.keyword);
    if (expected == formula.end()) continue;
    const double K = expected->second.K, C = expected->second.C;
    EXPECT_NEAR(spring->K, K, 1e-12 * K);
    EXPECT_NEAR(spring->C, C, 1e-12 * std::max(C, 1e-300));
    const double omega = std::sqrt(K / I_red), zeta = C / (2.0 * std::sqrt(K * I_red));
    const double dt = (2.0 / omega) * (std::sqrt(1.0 + zeta * zeta) - zeta);
    std::string mode;
    const double got = contact_critical_step(laws, p, {m, I, R}, {m, I, R}, &mode);
    EXPECT_EQ(mode, "rolling");
    EXPECT_NEAR(got, dt, 1e-12 * dt);
  }
  EXPECT_GE(with_spring, static_cast<int>(formula.size())) << "every law of the formula table has a spring";
}

const std::string kBase = R"(
[domain]
xlo = 0
xhi = 0.2
ylo = 0
yhi = 0.1
[linear]
k_n = 1e5
[scene]
type = lattice_square
nx = 2
ny = 1
radius = 0.005
x0 = 0.01
y0 = 0.01
)";

// The overrides that select `law` of `kind` with every required parameter of its block set to 1, the normal law
// it needs (with that law's examples) and the materials' elastic constants where it needs them.
std::vector<std::string> selecting(const LawKind& kind, const LawInfo& law) {
  const LawCatalog& catalog = law_catalog();
  std::vector<std::string> out{"--contact." + std::string(kind.kind) + "=" + law.keyword};
  if (&kind != &catalog.tangential) out.insert(out.end(), {"--coulomb.k_s=1e4", "--coulomb.mu=0.5"});
  if (law.needs_normal) {
    out.push_back("--contact.normal=" + std::string(law.needs_normal));
    const LawInfo* normal = catalog.normal.find(law.needs_normal);
    if (normal->block)
      for (const std::string& o : normal->block->example_options()) out.push_back(o);
  }
  if (law.elastic || (law.needs_normal && catalog.normal.find(law.needs_normal)->elastic))
    out.insert(out.end(), {"--material.youngs_modulus=7e10", "--material.poisson_ratio=0.25"});
  if (law.block)
    for (const ParamSpec& p : law.block->params)
      if (p.presence == Presence::required) out.push_back("--" + std::string(law.block->section) + "." + p.key + "=1");
  return out;
}

TEST(LawRegistry, ResolvedTextHoldsExactlyTheSelectedLawsBlock) {
  const LawCatalog& catalog = law_catalog();
  for (const LawKind* kind : {&catalog.tangential, &catalog.rolling})
    for (const LawInfo& law : kind->laws) {
      SCOPED_TRACE(std::string(kind->kind) + " " + law.keyword);
      std::string base = kBase;
      if (law.needs_normal) base.replace(base.find("[linear]"), 19, "");  // the law's own normal law instead
      const Config c = parse_config_text(base, selecting(*kind, law));
      for (const LawInfo& other : kind->laws) {
        if (!other.block) continue;
        const bool present = c.resolved_text.find("[" + std::string(other.block->section) + "]\n") != std::string::npos;
        EXPECT_EQ(present, other.block == law.block) << "[" << other.block->section << "] in\n" << c.resolved_text;
      }
    }
}

// A dashpot alone above the cap at t = 0: KernelOps::initial gives the capped forces of the initial state
// but leaves the springs as they were (a committing pass would reset them to -F/k, docs/physics.md section 1).
TEST(LawRegistry, InitialForcesCommitNoHistory) {
  ContactParams p;
  p.k_n = 1e5;
  p.k_s = 1e4;
  p.mu = 0.1;
  p.zeta_t = 0.5;
  p.k_r = 1e4;
  p.mu_r = 0.01;
  p.c_r = 1e3;
  const double R = 0.01, u0 = 1e-4;
  testing_rig::OneContactRig rig({"linear", "coulomb", "wang"}, p, R, R, u0, p.k_n * u0);
  rig.discs().velocity[0] = 10.0 * rig.t;
  rig.discs().omega[0] = 100.0;
  rig.start(1e-6);
  const ContactTable& row = rig.row_table();
  ASSERT_EQ(row.slot.size(), 2u);  // xi, x_r
  const double F_n = p.k_n * u0;
  EXPECT_NEAR(std::fabs(row.F_t[0]), p.mu * F_n, 1e-12 * F_n) << "the tangential dashpot alone is capped";
  EXPECT_NEAR(std::fabs(row.M1[0]), R / 2 * p.mu_r * F_n, 1e-12 * F_n) << "the rolling dashpot alone is capped";
  EXPECT_EQ(row.slot[0][0], 0.0) << "xi not committed";
  EXPECT_EQ(row.slot[1][0], 0.0) << "x_r not committed";
}

// A linear contact with Coulomb friction and wang's spring-slider, for the one-contact rigs below.
ContactParams wang_contact() {
  ContactParams p;
  p.k_n = 1e5;
  p.k_s = 1e4;
  p.mu = 0.5;
  p.k_r = 1e4;
  p.mu_r = 0.02;
  return p;
}
// The overrides that select wang (no dashpot) on kBase.
const std::vector<std::string> kWangOverrides{"--contact.rolling=wang", "--wang.k_r=1e4", "--wang.mu_r=0.1",
                                              "--coulomb.k_s=1e4", "--coulomb.mu=0.5"};

// Without a rolling dashpot anywhere (c_r = 0, the default) the kernel of rolling = wang is the one compiled
// without the dashpot's terms (RollingWangUndamped), and where moreover every pair and wall has rolling
// resistance (ContactParams::rolling, the default), the one that skips the per-contact test of p.rolling
// (RollingWangUndampedEveryRow). With c_r = 0 both perform the same operations as the full law, so every step's
// state and ledger terms carry the same bits: through loading, the cap, the reversal and the cap the other way,
// for two discs of equal and unequal radii and for a disc on a wall.
TEST(LawRegistry, WangWithoutADashpotGivesTheFullLawsBits) {
  const ContactParams p = wang_contact();
  const LawSelection full{"linear", "coulomb", "wang", false}, lean{"linear", "coulomb", "wang", true},
      every{"linear", "coulomb", "wang", true, true};
  EXPECT_NE(select_kernel(full).run, select_kernel(lean).run) << "the variant without a dashpot is selected";
  EXPECT_NE(select_kernel(full).initial, select_kernel(lean).initial);
  EXPECT_NE(select_kernel(lean).run, select_kernel(every).run) << "the variant without the p.rolling test";
  EXPECT_NE(select_kernel(full).run, select_kernel(every).run);
  const auto bits = [](double x) { return std::bit_cast<std::uint64_t>(x); };
  const double R = 0.01, u0 = 1e-4, dt = 1e-6;
  for (const LawSelection& variant : {lean, every}) {
    SCOPED_TRACE(variant.rolling_every_row ? "every row rolls" : "lean");
    for (const double R2 : {R, 0.6 * R, static_cast<double>(INFINITY)}) {
      SCOPED_TRACE("R2 = " + std::to_string(R2));
      testing_rig::OneContactRig a(full, p, R, R2, u0, p.k_n * u0), b(variant, p, R, R2, u0, p.k_n * u0);
      for (testing_rig::OneContactRig* rig : {&a, &b}) {
        rig->discs().omega[0] = 50.0;
        rig->start(dt);
      }
      int capped = 0, loaded = 0;
      for (int s = 0; s < 400; ++s) {
        if (s == 200)  // reverse the spin: the spring unloads and meets the cap the other way
          for (testing_rig::OneContactRig* rig : {&a, &b}) rig->discs().omega[0] = -50.0;
        LedgerStep la, lb;
        a.step(&la);
        b.step(&lb);
        const ContactTable &ta = a.row_table(), &tb = b.row_table();
        ASSERT_EQ(bits(ta.M1[0]), bits(tb.M1[0])) << "step " << s;
        ASSERT_EQ(bits(ta.slot[1][0]), bits(tb.slot[1][0])) << "x_r, step " << s;
        ASSERT_EQ(bits(ta.slot[0][0]), bits(tb.slot[0][0])) << "xi, step " << s;
        ASSERT_EQ(bits(ta.F_t[0]), bits(tb.F_t[0])) << "step " << s;
        for (std::size_t i = 0; i < a.discs().size(); ++i) {
          ASSERT_EQ(bits(a.discs().omega[i]), bits(b.discs().omega[i])) << "disc " << i << ", step " << s;
          ASSERT_EQ(bits(a.discs().velocity[i].x), bits(b.discs().velocity[i].x)) << "disc " << i << ", step " << s;
          ASSERT_EQ(bits(a.discs().velocity[i].y), bits(b.discs().velocity[i].y)) << "disc " << i << ", step " << s;
        }
        ASSERT_EQ(bits(la.W_r), bits(lb.W_r)) << "step " << s;
        ASSERT_EQ(bits(la.D_r_plastic), bits(lb.D_r_plastic)) << "step " << s;
        ASSERT_EQ(bits(la.D_r_dashpot), bits(lb.D_r_dashpot)) << "step " << s;
        ASSERT_EQ(bits(la.D_slip), bits(lb.D_slip)) << "step " << s;
        if (la.D_r_plastic > 0.0) ++capped;
        if (ta.M1[0] != 0.0 && la.D_r_plastic == 0.0) ++loaded;
      }
      EXPECT_GT(capped, 20) << "the rolling cap is reached";
      EXPECT_GT(loaded, 20) << "and the spring is loaded below it";
    }
  }
}

// The kernel without the p.rolling test is selected only where every pair and every wall has rolling
// resistance: one pair or one wall without (wall_contact.rolling = false, or a material pair's rolling = false)
// keeps the test. A pair without rolling resistance gets no couple from the lean kernel.
TEST(LawRegistry, TheKernelWithoutTheRollingTestOnlyWhereEveryRowRolls) {
  ContactParamTable t(2);
  EXPECT_TRUE(every_row_rolls(t));
  t.wall(1).rolling = false;
  EXPECT_FALSE(every_row_rolls(t)) << "a wall";
  t.wall(1).rolling = true;
  t.pair(0, 1).rolling = false;
  EXPECT_FALSE(every_row_rolls(t)) << "a pair of two materials";
  EXPECT_TRUE(law_selection(parse_config_text(kBase, kWangOverrides)).rolling_every_row);
  std::vector<std::string> no_wall_rolling = kWangOverrides;
  no_wall_rolling.push_back("--wall_contact.rolling=false");
  EXPECT_FALSE(law_selection(parse_config_text(kBase, no_wall_rolling)).rolling_every_row);

  // A pair without rolling resistance under the lean kernel that keeps the test: spun, it gets no couple.
  ContactParams p = wang_contact();
  p.rolling = false;
  const LawSelection lean{"linear", "coulomb", "wang", true, false};
  testing_rig::OneContactRig rig(lean, p, 0.01, 0.01, 1e-4, p.k_n * 1e-4);
  rig.discs().omega[0] = 50.0;
  rig.start(1e-6);
  for (int s = 0; s < 50; ++s) rig.step();
  EXPECT_EQ(rig.row_table().M1[0], 0.0) << "no rolling couple where p.rolling is false";
  EXPECT_EQ(rig.row_table().slot[1][0], 0.0) << "no rolling spring where p.rolling is false";
}

// The selection keeps the full law as soon as one pair or one wall of the table sets c_r > 0 (wang's lean(p) is
// false there), and a configuration without c_r selects the lean one.
TEST(LawRegistry, ARollingDashpotInAnyPairOrWallKeepsTheFullWangLaw) {
  ContactParams p;
  EXPECT_TRUE(RollingWang::lean(p));
  p.c_r = 0.5;
  EXPECT_FALSE(RollingWang::lean(p));
  EXPECT_TRUE(law_selection(parse_config_text(kBase, kWangOverrides)).rolling_lean);
  std::vector<std::string> damped = kWangOverrides;
  damped.push_back("--wang.c_r=2");
  EXPECT_FALSE(law_selection(parse_config_text(kBase, damped)).rolling_lean);
  std::vector<std::string> at_walls = kWangOverrides;
  at_walls.insert(at_walls.end(), {"--material.glass.density=2500", "--wang.glass.wall.glass.c_r=1"});
  EXPECT_FALSE(law_selection(parse_config_text(kBase, at_walls)).rolling_lean) << "one wall pair with a dashpot";
  std::vector<std::string> other = kWangOverrides;
  other.push_back("--contact.rolling=jiang_plastic");
  other.erase(other.begin(), other.begin() + 3);
  other.push_back("--jiang.delta=0.3");
  EXPECT_FALSE(law_selection(parse_config_text(kBase, other)).rolling_lean) << "a law without variants";
}

std::string config_error(const std::vector<std::string>& overrides) {
  try {
    parse_config_text(kBase, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted; expected a ConfigError";
  return "";
}

TEST(LawRegistry, EveryRequiredParameterAndEveryUnselectedBlockIsRefusedNamingTheKey) {
  const LawCatalog& catalog = law_catalog();
  for (const LawInfo& law : catalog.rolling.laws) {
    if (!law.block) continue;
    SCOPED_TRACE(law.keyword);
    const std::vector<std::string> all = selecting(catalog.rolling, law);
    for (const ParamSpec& p : law.block->params) {
      const std::string key = std::string(law.block->section) + "." + p.key;
      if (p.presence == Presence::required) {
        std::vector<std::string> missing;
        for (const std::string& o : all)
          if (o.rfind("--" + key + "=", 0) != 0) missing.push_back(o);
        EXPECT_NE(config_error(missing).find(key), std::string::npos) << key << " missing";
      }
      // The same key with rolling = none: a block of a law that is not selected.
      const std::string value = p.words.empty() ? "1" : p.words.front();  // a value its own check lets pass
      const std::string message =
          config_error({"--coulomb.k_s=1e4", "--coulomb.mu=0.5", "--contact.rolling=none", "--" + key + "=" + value});
      EXPECT_NE(message.find(key), std::string::npos) << message;
      EXPECT_NE(message.find("contact.rolling = none"), std::string::npos) << message;
    }
  }
}

}  // namespace
}  // namespace rondel
