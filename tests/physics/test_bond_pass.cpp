// The parallel bonds' rows (physics/BondPass.hpp, docs/physics.md section 12) on D5 discs (Rb = 5 mm, A = 0.01 m^2;
// kb_n = 1e9 Pa/m, kb_s = 0.5e9 Pa/m):
//  - creation: a bond for each candidate pair of bonded materials (kb_n > 0) whose gap is at most bonds.gap x the
//    smaller radius, none between two discs of one rigid body or of an unbonded pair of materials;
//  - a pair pulled apart through the pass: the forces in the sums (disc 1 pulled along +n by Fb_n = kb_n A delta,
//    disc 2 the opposite), W_b = -(the stored energy) every step to round-off, the break in the step where Fb_n/A
//    reaches sigma_c, its record (mode, centre halfway across the gap, stresses), the row removed and the energy
//    that was stored booked as E_b_break, so that W_b + E_b_break = 0 once it has broken;
//  - a row whose disc 1 is a ghost acts on the sums and breaks alike, but books nothing and records nothing;
//  - relink after a rebuild: local indices from the gids, rows with no owned disc dropped, a missing partner named;
//  - the critical step of a bonded pair: the bond's springs kb_n A, kb_s A and kb_n I added to the contact's normal,
//    tangential and rolling springs (equal discs: the tangential and rolling modes decouple), the mode named.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "physics/BondPass.hpp"
#include "physics/CriticalTimeStep.hpp"
#include "support/StandardObjects.hpp"

namespace rondel {
namespace {

constexpr double kR = test::d5::R;
constexpr double kDt = 1e-6;

ContactParamTable bonded_params(double sigma_c = 1e4, double tau_c = 1e9) {
  ContactParamTable t(2);  // material 0 bonds to itself only
  ContactParams& p = t.pair(0, 0);
  p.kb_n = 1e9, p.kb_s = 0.5e9, p.sigma_c = sigma_c, p.tau_c = tau_c;
  return t;
}

Domain box() {
  Domain d;
  d.xlo = -1.0, d.xhi = 1.0, d.ylo = -1.0, d.yhi = 1.0;
  return d;
}

DiscStore discs_at(const std::vector<Vec2>& x, const std::vector<int>& material = {}) {
  DiscStore d;
  for (std::size_t i = 0; i < x.size(); ++i)
    d.add(static_cast<std::int64_t>(i), material.empty() ? 0 : material[i], kR, test::d5::density, 1.0, x[i]);
  d.set_owned_count(d.size());
  return d;
}

// The candidate pair rows of every pair of `d` (as the neighbour list would give them within reach).
ContactTable all_pairs(const DiscStore& d, const ContactParamTable& params) {
  ContactTable t({}, 0);
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t j = i + 1; j < d.size(); ++j)
      t.push({d.gid[i], d.gid[j]}, static_cast<std::int32_t>(i), static_cast<std::int32_t>(j),
             static_cast<std::int32_t>(
                 params.pair_index(static_cast<std::size_t>(d.material[i]), static_cast<std::size_t>(d.material[j]))));
  return t;
}

TEST(BondPass, CreationBondsThePairsOfBondedMaterialsWithinTheGap) {
  const ContactParamTable params = bonded_params();
  // 0-1 touch, 1-2 at a gap of 0.009 R (bonded at gap 0.01), 2-3 at 0.011 R (not), 3-4 of materials 0 and 1.
  const double g1 = 0.009 * kR, g2 = 0.011 * kR;
  const double x2 = 4 * kR + g1, x3 = x2 + 2 * kR + g2, x4 = x3 + 2 * kR;
  DiscStore d = discs_at({{0, 0}, {2 * kR, 0}, {x2, 0}, {x3, 0}, {x4, 0}}, {0, 0, 0, 0, 1});
  ContactTable bonds = ContactTable::bond_table();
  bonds::create(d, box(), params, all_pairs(d, params), 0.01, bonds);
  ASSERT_EQ(bonds.size(), 2u);
  EXPECT_EQ(bonds.key[0], (ContactKey{0, 1}));
  EXPECT_EQ(bonds.key[1], (ContactKey{1, 2}));
  // Two discs of one rigid body (both fixed) are not bonded.
  d.flags[0] = d.flags[1] = kFlagFixed;
  ContactTable again = ContactTable::bond_table();
  bonds::create(d, box(), params, all_pairs(d, params), 0.01, again);
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again.key[0], (ContactKey{1, 2}));
}

struct Pulled {
  int broke_at = -1;
  std::vector<BondBreak> breaks;
  double W = 0.0, E_break = 0.0;
  double worst_balance = 0.0;  // max |W_b + stored| / stored while intact
  double worst_force = 0.0;    // max |Fb_n - kb_n A delta| / (kb_n A delta)
  bool forces_on_sums = true;  // the sums hold +Fb_n n on disc 1 and -Fb_n n on disc 2 (to round-off)
  std::size_t rows_after = 0;
};

// Disc 2 (gid 1) leaves at V along +x from contact; `owned`: how many discs this rank owns (1: disc 2 only, as
// the gids are stored in reverse so that disc 1 of the bond is the ghost).
Pulled pull(double sigma_c, double V, int steps, bool disc1_ghost = false) {
  const ContactParamTable params = bonded_params(sigma_c);
  DiscStore d;
  if (!disc1_ghost) {
    d = discs_at({{0, 0}, {2 * kR, 0}});
  } else {  // owned: gid 1 (index 0); ghost: gid 0 (index 1)
    d.add(1, 0, kR, test::d5::density, 1.0, {2 * kR, 0});
    d.add(0, 0, kR, test::d5::density, 1.0, {0, 0});
    d.set_owned_count(1);
  }
  const std::size_t moving = disc1_ghost ? 0 : 1;
  d.velocity[moving] = {V, 0};
  ContactTable bonds = ContactTable::bond_table();
  ContactTable pairs({}, 0);
  pairs.push({0, 1}, disc1_ghost ? 1 : 0, disc1_ghost ? 0 : 1, 0);
  bonds::create(d, box(), params, pairs, 0.01, bonds);
  EXPECT_EQ(bonds.size(), 1u);
  const BondGeometry g = BondGeometry::of(kR, kR, 1.0, 1.0);
  Pulled out;
  LedgerTerms terms;
  for (int s = 1; s <= steps && out.broke_at < 0; ++s) {
    d.position[moving] += kDt * d.velocity[moving];
    for (auto& f : d.force) f = {};
    for (auto& t : d.torque) t = 0.0;
    bonds::step(BondContext{d, box(), params, 1.0, kDt}, bonds, ForceSums::of(d), terms, out.breaks);
    if (bonds.size() == 0) {
      out.broke_at = s;
      break;
    }
    const double delta = V * kDt * s, expected = 1e9 * g.A * delta;
    out.worst_force = std::max(out.worst_force, std::fabs(bonds.slot[0][0] - expected) / expected);
    const std::size_t one = disc1_ghost ? 1 : 0, two = 1 - one;
    const double F = bonds.slot[0][0];  // n = d/|d| is (1, 0) to an ulp
    out.forces_on_sums = out.forces_on_sums && std::fabs(d.force[one].x - F) <= 1e-15 * F &&
                         std::fabs(d.force[two].x + F) <= 1e-15 * F && d.force[one].y == 0.0;
    const double stored = bonds::stored(BondContext{d, box(), params, 1.0, kDt}, bonds);
    if (stored > 0.0) out.worst_balance = std::max(out.worst_balance, std::fabs(terms.W_b + stored) / stored);
  }
  out.W = terms.W_b, out.E_break = terms.E_b_break;
  out.rows_after = bonds.size();
  return out;
}

TEST(BondPass, APulledPairCarriesItsForceBooksItsWorkAndBreaksInTension) {
  const double V = 0.01;                     // Fb_n/A grows by kb_n V dt = 10 Pa a step
  const Pulled p = pull(1.0505e4, V, 3000);  // reached in step 1051
  EXPECT_EQ(p.broke_at, 1051);
  EXPECT_LT(p.worst_force, 1e-12);
  EXPECT_TRUE(p.forces_on_sums);
  EXPECT_LT(p.worst_balance, 1e-12);
  ASSERT_EQ(p.breaks.size(), 1u);
  const BondBreak& b = p.breaks[0];
  EXPECT_EQ(b.key, (ContactKey{0, 1}));
  EXPECT_EQ(b.mode, BondMode::tension);
  EXPECT_GE(b.sigma, 1.0505e4);
  EXPECT_LT(b.sigma, 1.0505e4 + 10.0 + 1e-6);
  EXPECT_DOUBLE_EQ(b.tau, 0.0);
  const double gap = V * kDt * 1051;  // the centre: halfway across the gap
  EXPECT_NEAR(b.position.x, kR + 0.5 * gap, 1e-15);
  EXPECT_DOUBLE_EQ(b.position.y, 0.0);
  EXPECT_EQ(p.rows_after, 0u);
  // What the bond took from the motion, it released when it broke.
  EXPECT_GT(p.E_break, 0.0);
  EXPECT_NEAR(p.W + p.E_break, 0.0, 1e-12 * p.E_break);
}

TEST(BondPass, ARowWhoseFirstDiscIsAGhostActsAndBreaksButBooksNothing) {
  const Pulled mine = pull(1.0505e4, 0.01, 3000);
  const Pulled ghost = pull(1.0505e4, 0.01, 3000, true);
  EXPECT_EQ(ghost.broke_at, mine.broke_at);
  EXPECT_TRUE(ghost.forces_on_sums);
  EXPECT_LT(ghost.worst_force, 1e-12);
  EXPECT_EQ(ghost.breaks.size(), 0u);
  EXPECT_EQ(ghost.W, 0.0);
  EXPECT_EQ(ghost.E_break, 0.0);
  EXPECT_EQ(ghost.rows_after, 0u);
}

TEST(BondPass, RelinkFindsTheDiscsByGidDropsRowsWithNoOwnedDiscAndNamesALostPartner) {
  // Owned: gids 5 and 2 (indices 0, 1); ghosts: gids 9 and 1 (indices 2, 3).
  DiscStore d;
  for (std::int64_t gid : {5, 2, 9, 1}) d.add(gid, 0, kR, test::d5::density, 1.0, {0.1 * gid, 0});
  d.set_owned_count(2);
  ContactTable t = ContactTable::bond_table();
  for (ContactKey k : {ContactKey{1, 2}, ContactKey{1, 9}, ContactKey{2, 5}, ContactKey{5, 9}}) t.push(k, -1, -1, 0);
  t.slot[0][2] = 3.5;  // the state travels with the row
  ContactKey lost{-1, -1};
  EXPECT_TRUE(bonds::relink(d, t, lost));
  ASSERT_EQ(t.size(), 3u);  // (1, 9): two ghosts, dropped
  EXPECT_EQ(t.key[0], (ContactKey{1, 2}));
  EXPECT_EQ(t.i1[0], 3);
  EXPECT_EQ(t.i2[0], 1);
  EXPECT_EQ(t.key[1], (ContactKey{2, 5}));
  EXPECT_EQ(t.i1[1], 1);
  EXPECT_EQ(t.i2[1], 0);
  EXPECT_EQ(t.slot[0][1], 3.5);
  EXPECT_EQ(t.key[2], (ContactKey{5, 9}));
  // A partner that is not here (gid 7): the row cannot act, and relink says which.
  t.push({2, 7}, -1, -1, 0);
  EXPECT_FALSE(bonds::relink(d, t, lost));
  EXPECT_EQ(lost, (ContactKey{2, 7}));
}

TEST(BondPass, TheCriticalStepOfABondedPairAddsTheBondsSprings) {
  ContactParams p = test::set_S();  // k_n = 1e6, k_s = 7.5e5, no damping
  const double m = test::d5::mass(), I = test::d5::inertia();
  const ContactBody disc{m, I, kR};
  const LawSelection laws;  // linear, coulomb, no rolling law
  std::string mode;
  const double plain = contact_critical_step(laws, p, disc, disc, &mode, 0.1, 1.0);
  EXPECT_EQ(mode.find("bond"), std::string::npos) << mode;
  p.kb_n = 1e9, p.kb_s = 0.5e9;
  const double bonded = contact_critical_step(laws, p, disc, disc, &mode, 0.1, 1.0);
  const BondGeometry g = BondGeometry::of(kR, kR, 1.0, 1.0);
  const double w2_n = (p.k_n + p.kb_n * g.A) / (0.5 * m);
  const double w2_t = (p.k_s + p.kb_s * g.A) * 2.0 * (1.0 / m + kR * kR / I);  // 1/m_t of two equal discs
  const double w2_r = p.kb_n * g.I * 2.0 / I;                                  // I_red = I/2
  const double expected = 2.0 / std::sqrt(std::max({w2_n, w2_t, w2_r}));
  EXPECT_NEAR(bonded / expected, 1.0, 1e-12);
  EXPECT_LT(bonded, plain);
  EXPECT_EQ(mode, "tangential + bond");  // the coupled mode equals it here (C = 0): the first found is kept
  // Without the thickness (a caller that knows of no bonds) the bond is left out.
  EXPECT_EQ(contact_critical_step(laws, p, disc, disc, &mode), plain);
}

}  // namespace
}  // namespace rondel
