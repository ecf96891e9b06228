// ForceAssembly (src/core/ForceAssembly.*): each owned disc's force and torque are summed in one fixed
// order (docs/design.md section 4, step 6): gravity m g first, then the pair rows by ascending partner gid,
// then the wall rows by ascending wall id, whatever the storage order of discs and rows. Fixed discs get
// zero, except that a disc glued to a wall keeps its contact force (no gravity, no torque). The addends
// below are chosen so that any other order gives other bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/ForceAssembly.hpp"
#include "support/Assertions.hpp"

namespace rondel {
namespace {

using test::same_bits;

constexpr Vec2 kGravity{0.3, -9.81};

// One contribution to disc `gid`: from partner `partner` (a disc gid, or a wall id when `wall`).
struct Term {
  std::int64_t partner;
  bool wall;
  Vec2 f;
  double tq;
};

// Rows with magnitudes 1e16 and 1 mixed: their floating-point sum depends on the order of the additions.
double magnitude(std::mt19937_64& rng) {
  static const double choices[] = {1e16, -1e16, 1.0, -3.0, 0.1, 7e15};
  return choices[rng() % 6];
}

struct Scene {
  DiscStore discs;
  ContactTable pairs{{}, false}, walls{{}, false};
  std::vector<std::int64_t> gids;
};

// Discs gid 10..10+n-1 stored shuffled; every pair (a, b) with a < b present with probability 1/2;
// walls 0..2 touching some discs; rows pushed in a shuffled order.
Scene make_scene(unsigned seed, int n) {
  std::mt19937_64 rng(seed);
  Scene s;
  for (int k = 0; k < n; ++k) s.gids.push_back(10 + k);
  std::shuffle(s.gids.begin(), s.gids.end(), rng);
  for (std::size_t i = 0; i < s.gids.size(); ++i)
    s.discs.add(s.gids[i], 0, 0.001 * (1 + i % 3), 2650.0, 1.0, {0.01 * static_cast<double>(i), 0.0});
  std::vector<std::tuple<std::int32_t, std::int32_t>> pair_rows, wall_rows;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (s.gids[a] < s.gids[b] && rng() % 2) pair_rows.emplace_back(a, b);
  for (int a = 0; a < n; ++a)
    for (int w = 0; w < 3; ++w)
      if (rng() % 3 == 0) wall_rows.emplace_back(a, w);
  std::shuffle(pair_rows.begin(), pair_rows.end(), rng);
  std::shuffle(wall_rows.begin(), wall_rows.end(), rng);
  for (const auto& [a, b] : pair_rows) {
    s.pairs.push(ContactKey{s.gids[a], s.gids[b]}, a, b, 0);
    s.pairs.f1.back() = {magnitude(rng), magnitude(rng)};
    s.pairs.tq1.back() = magnitude(rng);
    s.pairs.tq2.back() = magnitude(rng);
  }
  for (const auto& [a, w] : wall_rows) {
    s.walls.push(ContactKey{s.gids[a], w}, a, w, 0);
    s.walls.f1.back() = {magnitude(rng), magnitude(rng)};
    s.walls.tq1.back() = magnitude(rng);
  }
  return s;
}

// The terms of disc i in the documented order: pair partners by gid, then walls by id.
std::vector<Term> terms_in_order(const Scene& s, std::size_t i) {
  std::vector<Term> t;
  const std::int64_t g = s.discs.gid[i];
  for (std::size_t r = 0; r < s.pairs.size(); ++r) {
    if (s.pairs.key[r].lo == g) t.push_back({s.pairs.key[r].hi, false, s.pairs.f1[r], s.pairs.tq1[r]});
    if (s.pairs.key[r].hi == g) t.push_back({s.pairs.key[r].lo, false, -1.0 * s.pairs.f1[r], s.pairs.tq2[r]});
  }
  for (std::size_t r = 0; r < s.walls.size(); ++r)
    if (s.walls.key[r].lo == g) t.push_back({s.walls.key[r].hi, true, s.walls.f1[r], s.walls.tq1[r]});
  std::sort(t.begin(), t.end(),
            [](const Term& a, const Term& b) { return std::tie(a.wall, a.partner) < std::tie(b.wall, b.partner); });
  return t;
}

void expect_documented_order(Scene& s) {
  ForceAssembly fa;
  fa.build(s.discs, s.pairs, s.walls);
  fa.assemble(s.discs, BodyForce{kGravity}, s.pairs, s.walls);
  for (std::size_t i = 0; i < s.discs.n_owned(); ++i) {
    const bool fixed = s.discs.flags[i] & kFlagFixed, glued = is_attached(s.discs.flags[i]);
    Vec2 F = fixed ? Vec2{} : s.discs.mass[i] * kGravity;
    double T = 0.0;
    for (const Term& t : terms_in_order(s, i)) {
      F += t.f;
      T += t.tq;
    }
    if (fixed) {
      if (!glued) F = {};
      T = 0.0;
    }
    EXPECT_TRUE(same_bits(s.discs.force[i].x, F.x)) << "disc gid " << s.discs.gid[i];
    EXPECT_TRUE(same_bits(s.discs.force[i].y, F.y)) << "disc gid " << s.discs.gid[i];
    EXPECT_TRUE(same_bits(s.discs.torque[i], T)) << "disc gid " << s.discs.gid[i];
  }
}

TEST(ForceAssembly, SumsGravityThenPartnersByGidThenWalls) {
  for (unsigned seed : {1u, 2u, 3u}) {
    Scene s = make_scene(seed, 12);
    expect_documented_order(s);
  }
}

// The same contacts with the rows in reverse order.
ContactTable reversed(const ContactTable& t) {
  ContactTable out({}, false);
  for (std::size_t r = t.size(); r-- > 0;) {
    out.push(t.key[r], t.i1[r], t.i2[r], t.param[r]);
    out.f1.back() = t.f1[r];
    out.tq1.back() = t.tq1[r];
    out.tq2.back() = t.tq2[r];
  }
  return out;
}

TEST(ForceAssembly, RowOrderDoesNotChangeTheBits) {
  Scene a = make_scene(4, 10);
  Scene b = make_scene(4, 10);
  const ContactTable pairs = reversed(b.pairs), walls = reversed(b.walls);
  ForceAssembly fa, fb;
  fa.build(a.discs, a.pairs, a.walls);
  fa.assemble(a.discs, BodyForce{kGravity}, a.pairs, a.walls);
  fb.build(b.discs, pairs, walls);
  fb.assemble(b.discs, BodyForce{kGravity}, pairs, walls);
  for (std::size_t i = 0; i < a.discs.n_owned(); ++i) {
    EXPECT_TRUE(same_bits(a.discs.force[i].x, b.discs.force[i].x)) << "disc gid " << a.discs.gid[i];
    EXPECT_TRUE(same_bits(a.discs.force[i].y, b.discs.force[i].y)) << "disc gid " << a.discs.gid[i];
    EXPECT_TRUE(same_bits(a.discs.torque[i], b.discs.torque[i])) << "disc gid " << a.discs.gid[i];
  }
}

TEST(ForceAssembly, DiscWithoutContactsGetsGravityOnly) {
  DiscStore discs;
  discs.add(5, 0, 0.002, 2650.0, 1.0, {0.0, 0.0});
  ContactTable pairs({}, false), walls({}, false);
  ForceAssembly fa;
  fa.build(discs, pairs, walls);
  fa.assemble(discs, BodyForce{kGravity}, pairs, walls);
  EXPECT_TRUE(same_bits(discs.force[0].x, discs.mass[0] * kGravity.x));
  EXPECT_TRUE(same_bits(discs.force[0].y, discs.mass[0] * kGravity.y));
  EXPECT_EQ(discs.torque[0], 0.0);
}

TEST(ForceAssembly, FixedDiscsGetNothingGluedDiscsKeepTheirContactForce) {
  Scene s = make_scene(5, 9);
  s.discs.flags[1] = kFlagFixed;
  s.discs.flags[4] = attached_flags(2);
  expect_documented_order(s);
  EXPECT_EQ(s.discs.force[1].x, 0.0);
  EXPECT_EQ(s.discs.force[1].y, 0.0);
  EXPECT_EQ(s.discs.torque[1], 0.0);
  EXPECT_EQ(s.discs.torque[4], 0.0);
}

TEST(ForceAssembly, GhostsAreNotAssembled) {
  // A pair row between an owned disc and a ghost contributes to the owned disc only.
  DiscStore discs;
  discs.add(1, 0, 0.002, 2650.0, 1.0, {0.0, 0.0});
  discs.add(2, 0, 0.002, 2650.0, 1.0, {0.003, 0.0});
  discs.set_owned_count(1);
  ContactTable pairs({}, false), walls({}, false);
  pairs.push(ContactKey{1, 2}, 0, 1, 0);
  pairs.f1.back() = {2.0, -1.0};
  pairs.tq1.back() = 0.5;
  pairs.tq2.back() = 0.25;
  ForceAssembly fa;
  fa.build(discs, pairs, walls);
  fa.assemble(discs, BodyForce{Vec2{}}, pairs, walls);
  EXPECT_EQ(discs.force[0].x, 2.0);
  EXPECT_EQ(discs.force[0].y, -1.0);
  EXPECT_EQ(discs.torque[0], 0.5);
}

}  // namespace
}  // namespace rondel
