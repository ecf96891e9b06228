// The per-disc sums of the step (docs/design.md sections 4 and 5, step 6): each owned disc's force and torque
// are the body force, then its contact terms in ascending partner gid, then its wall terms by wall id. The
// contact kernel adds each row's terms as it goes (physics/ContactKernel.hpp: rows in ascending key order
// give that order for every disc); ForceAssembly starts the sums and finishes the fixed discs. These tests
// run the real kernel on a cluster of overlapping discs whose contacts have stiffnesses from 1 to 1e16, so
// that their floating-point sum depends on the order of the additions, and compare with sums formed in the
// documented order from each row's own terms, and across storage orders of the discs.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/ForceAssembly.hpp"
#include "core/Wall.hpp"
#include "physics/ContactKernel.hpp"
#include "physics/LawRegistry.hpp"
#include "support/Assertions.hpp"

namespace rondel {
namespace {

using test::same_bits;

constexpr Vec2 kGravity{0.3, -9.81};
const LawSelection kLaws{"linear", "coulomb", "wang"};

struct Scene {
  DiscStore discs;
  ContactParamTable params{4};
  Domain domain{-1.0, 1.0, -1.0, 1.0, false, false};
  WallSet walls;
  ContactTable pairs = make_contact_table(kLaws, false), wall_rows = make_contact_table(kLaws, true);
};

// Discs gid 10..10+n-1 in a cluster (most pairs overlap), stored in the order `order` (a permutation of
// 0..n-1: disc k of the cluster is stored at position order[k]); each disc-disc row takes one of 16
// parameter entries with k_n from 1 to 1e16; two walls, a floor and a left side, touch some discs. Rows are
// in ascending key order (as the neighbour list builds them). Each disc has a spin and a velocity, so that
// tangential and rolling terms are not zero.
Scene make_scene(unsigned seed, int n, const std::vector<int>& order, std::uint32_t fixed_flags = 0, int fixed = -1) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  struct Disc {
    std::int64_t gid;
    double R;
    Vec2 x, v;
    double w;
  };
  std::vector<Disc> cluster;
  for (int k = 0; k < n; ++k)
    cluster.push_back(
        {10 + k, 0.04 + 0.01 * (k % 3), {0.06 * u(rng), -0.94 + 0.06 * u(rng)}, {u(rng), u(rng)}, u(rng)});
  Scene s;
  const double stiffness[] = {1.0, 1e16, 0.1, 7e15};
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 4; ++b) {
      ContactParams& p = s.params.pair(a, b);
      p.k_n = stiffness[a] * (b + 1.0);
      p.zeta_n = 0.1;
      p.k_s = 0.5 * p.k_n;
      p.mu = 0.5;
      p.k_r = 0.3 * p.k_n;
      p.mu_r = 0.1;
      s.params.wall(a, b) = p;
    }
  std::vector<int> slot(n);
  for (int k = 0; k < n; ++k) slot[order[k]] = k;
  for (int pos = 0; pos < n; ++pos) {
    const Disc& d = cluster[slot[pos]];
    s.discs.add(d.gid, 0, d.R, 2650.0, 1.0, d.x, d.v, d.w);
    if (slot[pos] == fixed) s.discs.flags.back() = fixed_flags;
  }
  Wall floor;
  floor.p0 = {0.0, -1.0};
  floor.normal = {0.0, 1.0};
  Wall side = floor;
  side.p0 = {-0.05, 0.0};
  side.normal = {1.0, 0.0};
  s.walls = {floor, side};
  std::vector<std::tuple<ContactKey, std::int32_t, std::int32_t>> rows;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      if (s.discs.gid[i] < s.discs.gid[j]) rows.emplace_back(ContactKey{s.discs.gid[i], s.discs.gid[j]}, i, j);
  std::sort(rows.begin(), rows.end());
  for (const auto& [key, i, j] : rows)
    s.pairs.push(key, i, j, static_cast<std::int32_t>((key.lo * 7 + key.hi * 3) % 16));
  std::vector<std::tuple<std::int64_t, int>> by_gid;
  for (int i = 0; i < n; ++i) by_gid.emplace_back(s.discs.gid[i], i);
  std::sort(by_gid.begin(), by_gid.end());
  for (const auto& [gid, i] : by_gid)
    for (int w = 0; w < 2; ++w) s.wall_rows.push(ContactKey{gid, w}, i, w, static_cast<std::int32_t>(gid % 16));
  return s;
}

// One step of the kernel with the sums begun and finished as Simulation::step does it.
void kernel_step(Scene& s) {
  const KernelOps ops = select_kernel(kLaws);
  ForceAssembly assembly;
  assembly.build(s.discs);
  ForceAssembly::begin(s.discs, BodyForce{kGravity});
  LedgerStep ledger;
  ops.run(KernelContext{s.discs, s.domain, s.walls, s.params, 1e-4}, s.pairs, s.wall_rows, ForceSums::of(s.discs),
          ledger);
  assembly.finish(s.discs);
}

// A term of disc `gid`'s sum: from partner `partner` (a disc gid, or a wall id when `wall`).
struct Term {
  bool wall;
  std::int64_t partner;
  Vec2 f;
  double tq;
};

// Every row's own terms, found by running the kernel on that row alone into zeroed sums (0 + x = x).
std::map<std::int64_t, std::vector<Term>> terms_of_rows(const Scene& s) {
  std::map<std::int64_t, std::vector<Term>> terms;
  const KernelOps ops = select_kernel(kLaws);
  for (int table = 0; table < 2; ++table) {
    const ContactTable& rows = table == 0 ? s.pairs : s.wall_rows;
    for (std::size_t r = 0; r < rows.size(); ++r) {
      Scene one = s;
      one.pairs = s.pairs.empty_like();
      one.wall_rows = s.wall_rows.empty_like();
      ContactTable& into = table == 0 ? one.pairs : one.wall_rows;
      into.push_copy(rows, r);
      into.i1.back() = rows.i1[r];
      into.i2.back() = rows.i2[r];
      std::fill(one.discs.force.begin(), one.discs.force.end(), Vec2{});
      std::fill(one.discs.torque.begin(), one.discs.torque.end(), 0.0);
      LedgerStep ledger;
      ops.run(KernelContext{one.discs, one.domain, one.walls, one.params, 1e-4}, one.pairs, one.wall_rows,
              ForceSums::of(one.discs), ledger);
      const auto i = static_cast<std::size_t>(rows.i1[r]);
      terms[rows.key[r].lo].push_back({table == 1, rows.key[r].hi, one.discs.force[i], one.discs.torque[i]});
      if (table == 0) {
        const auto j = static_cast<std::size_t>(rows.i2[r]);
        terms[rows.key[r].hi].push_back({false, rows.key[r].lo, one.discs.force[j], one.discs.torque[j]});
      }
    }
  }
  for (auto& [gid, t] : terms)
    std::sort(t.begin(), t.end(),
              [](const Term& a, const Term& b) { return std::tie(a.wall, a.partner) < std::tie(b.wall, b.partner); });
  return terms;
}

std::vector<int> identity(int n) {
  std::vector<int> order(n);
  for (int k = 0; k < n; ++k) order[k] = k;
  return order;
}

TEST(ForceSums, BodyForceThenPartnersByGidThenWalls) {
  for (unsigned seed : {1u, 2u, 3u}) {
    std::vector<int> order = identity(12);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(seed + 100));
    Scene s = make_scene(seed, 12, order);
    const auto terms = terms_of_rows(s);
    kernel_step(s);
    int loaded = 0;
    for (std::size_t i = 0; i < s.discs.n_owned(); ++i) {
      Vec2 F = s.discs.mass[i] * kGravity;
      double T = 0.0;
      for (const Term& t : terms.at(s.discs.gid[i])) {
        F += t.f;
        T += t.tq;
        loaded += t.tq != 0.0;
      }
      EXPECT_TRUE(same_bits(s.discs.force[i].x, F.x)) << "seed " << seed << ", disc gid " << s.discs.gid[i];
      EXPECT_TRUE(same_bits(s.discs.force[i].y, F.y)) << "seed " << seed << ", disc gid " << s.discs.gid[i];
      EXPECT_TRUE(same_bits(s.discs.torque[i], T)) << "seed " << seed << ", disc gid " << s.discs.gid[i];
    }
    EXPECT_GT(loaded, 40) << "the cluster has too few loaded contacts to test the order";
  }
}

// The same discs stored in other orders: the same bits for every disc, though the sums of these contacts
// depend on the order of their additions (the kernel's order is that of the keys, not of the storage).
TEST(ForceSums, StorageOrderDoesNotChangeTheBits) {
  const int n = 12;
  Scene a = make_scene(4, n, identity(n));
  kernel_step(a);
  std::map<std::int64_t, std::tuple<Vec2, double>> first;
  for (std::size_t i = 0; i < a.discs.n_owned(); ++i) first[a.discs.gid[i]] = {a.discs.force[i], a.discs.torque[i]};
  for (unsigned seed : {5u, 6u}) {
    std::vector<int> order = identity(n);
    std::shuffle(order.begin(), order.end(), std::mt19937_64(seed));
    Scene b = make_scene(4, n, order);
    kernel_step(b);
    for (std::size_t i = 0; i < b.discs.n_owned(); ++i) {
      const auto& [F, T] = first.at(b.discs.gid[i]);
      EXPECT_TRUE(same_bits(b.discs.force[i].x, F.x)) << "disc gid " << b.discs.gid[i];
      EXPECT_TRUE(same_bits(b.discs.force[i].y, F.y)) << "disc gid " << b.discs.gid[i];
      EXPECT_TRUE(same_bits(b.discs.torque[i], T)) << "disc gid " << b.discs.gid[i];
    }
  }
}

TEST(ForceSums, FixedDiscsGetNothingGluedDiscsKeepTheirContactForce) {
  const int n = 9;
  for (std::uint32_t flags : {std::uint32_t{kFlagFixed}, attached_flags(1)}) {
    Scene s = make_scene(7, n, identity(n), flags, 4);
    const auto terms = terms_of_rows(s);
    kernel_step(s);
    Vec2 F;  // no body force on a fixed disc
    for (const Term& t : terms.at(s.discs.gid[4])) F += t.f;
    EXPECT_TRUE(same_bits(s.discs.force[4].x, is_attached(flags) ? F.x : 0.0));
    EXPECT_TRUE(same_bits(s.discs.force[4].y, is_attached(flags) ? F.y : 0.0));
    EXPECT_TRUE(same_bits(s.discs.torque[4], 0.0));
    EXPECT_NE(F.x, 0.0) << "the fixed disc has no loaded contact: the case tests nothing";
  }
}

TEST(ForceSums, ADiscWithoutContactsGetsTheBodyForceOnly) {
  Scene s = make_scene(8, 3, identity(3));
  s.discs.position[2] = {0.5, 0.5};
  kernel_step(s);
  EXPECT_TRUE(same_bits(s.discs.force[2].x, s.discs.mass[2] * kGravity.x));
  EXPECT_TRUE(same_bits(s.discs.force[2].y, s.discs.mass[2] * kGravity.y));
  EXPECT_TRUE(same_bits(s.discs.torque[2], 0.0));
}

TEST(ForceSums, GhostsReceiveScratchOnly) {
  // A pair of an owned disc and a ghost: the owned disc's sum has the term; begin() zeroes the ghost's
  // entries, which nothing reads.
  Scene s = make_scene(9, 2, identity(2));
  s.discs.set_owned_count(1);
  s.wall_rows = s.wall_rows.empty_like();
  s.discs.force[1] = {5.0, 5.0};
  const auto terms = terms_of_rows(s);
  kernel_step(s);
  ASSERT_EQ(terms.at(s.discs.gid[0]).size(), 1u);
  const Vec2 F = s.discs.mass[0] * kGravity + terms.at(s.discs.gid[0])[0].f;
  EXPECT_TRUE(same_bits(s.discs.force[0].x, F.x));
  EXPECT_TRUE(same_bits(s.discs.force[0].y, F.y));
  EXPECT_TRUE(same_bits(s.discs.force[1].x, -terms.at(s.discs.gid[0])[0].f.x)) << "begin() zeroes the ghost's sum";
}

}  // namespace
}  // namespace rondel
