// Neighbour search against brute force (docs/design.md section 9): the cell grid plus Verlet list must find
// exactly the pairs with gap < skin (|d| < R1 + R2 + skin, minimum image) and the wall rows with
// distance < R + skin, in ascending key order, carry history by key across rebuilds, and ask for a
// rebuild when a disc has moved more than half the skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Domain.hpp"
#include "core/NeighbourList.hpp"
#include "core/SceneBuilder.hpp"
#include "core/Wall.hpp"

namespace rondel {
namespace {

using KeyPair = std::pair<std::int64_t, std::int64_t>;

constexpr double kDensity = 2650.0;

struct Placed {
  std::int64_t gid;
  double R;
  Vec2 x;
};

double uniform(SceneRandom& rng, double lo, double hi) { return lo + rng.uniform() * (hi - lo); }

// Random discs (overlaps allowed: the search does not care) with scattered, non-contiguous gids, plus
// discs right at the box corners and edges. For a non-periodic direction some sit slightly outside the
// box (the grid clamps them into the edge cells); for a periodic one they stay in [lo, hi).
std::vector<Placed> random_discs(const Domain& d, std::size_t n, double R_min, double R_max, std::uint64_t seed) {
  SceneRandom rng(seed);
  std::vector<Placed> out;
  std::int64_t gid = 11;
  auto next_gid = [&]() { return gid += 1 + static_cast<std::int64_t>(rng.next() % 5); };
  for (std::size_t k = 0; k < n; ++k)
    out.push_back({next_gid(), uniform(rng, R_min, R_max), {uniform(rng, d.xlo, d.xhi), uniform(rng, d.ylo, d.yhi)}});
  const double x_top = d.periodic_x ? std::nextafter(d.xhi, d.xlo) : d.xhi;
  const double y_top = d.periodic_y ? std::nextafter(d.yhi, d.ylo) : d.yhi;
  const double xs[] = {d.xlo, x_top, 0.5 * (d.xlo + d.xhi), d.xlo + 0.25 * R_min, x_top - 0.25 * R_min};
  const double ys[] = {d.ylo, y_top, 0.5 * (d.ylo + d.yhi), d.ylo + 0.25 * R_min, y_top - 0.25 * R_min};
  for (double x : xs)
    for (double y : ys) out.push_back({next_gid(), uniform(rng, R_min, R_max), {x, y}});
  // Pairs straddling each edge at the same height / abscissa.
  for (int k = 0; k < 6; ++k) {
    const double y = uniform(rng, d.ylo, d.yhi), x = uniform(rng, d.xlo, d.xhi);
    out.push_back({next_gid(), R_max, {d.xlo + 0.1 * k * R_max, y}});
    out.push_back({next_gid(), R_min, {x_top - 0.1 * k * R_max, y}});
    out.push_back({next_gid(), R_max, {x, d.ylo + 0.1 * k * R_max}});
    out.push_back({next_gid(), R_min, {x, y_top - 0.1 * k * R_max}});
  }
  if (!d.periodic_x) {
    out.push_back({next_gid(), R_min, {d.xlo - 0.5 * R_min, uniform(rng, d.ylo, d.yhi)}});
    out.push_back({next_gid(), R_min, {d.xhi + 0.5 * R_min, uniform(rng, d.ylo, d.yhi)}});
  }
  if (!d.periodic_y) {
    out.push_back({next_gid(), R_min, {uniform(rng, d.xlo, d.xhi), d.ylo - 0.5 * R_min}});
    out.push_back({next_gid(), R_min, {uniform(rng, d.xlo, d.xhi), d.yhi + 0.5 * R_min}});
  }
  // Storage order is not gid order.
  for (std::size_t k = out.size(); k > 1; --k) std::swap(out[k - 1], out[rng.next() % k]);
  return out;
}

DiscStore make_store(const std::vector<Placed>& discs) {
  DiscStore s;
  for (const auto& p : discs) s.add(p.gid, 0, p.R, kDensity, 1.0, p.x);
  return s;
}

// Appends a ghost (a copy of another rank's disc) by growing every field, as the ghost exchange does.
void add_ghost(DiscStore& s, std::int64_t gid, double R, Vec2 x) {
  const std::size_t n = s.size() + 1;
  s.for_each_field([n](const char*, unsigned, auto& field) { field.resize(n); });
  s.gid.back() = gid;
  s.material.back() = 0;
  s.radius.back() = R;
  s.position.back() = x;
}

// Minimum image written independently of Domain::separation.
Vec2 min_image(const Domain& d, Vec2 a, Vec2 b) {
  Vec2 r = b - a;
  if (d.periodic_x) r.x -= d.length_x() * std::round(r.x / d.length_x());
  if (d.periodic_y) r.y -= d.length_y() * std::round(r.y / d.length_y());
  return r;
}

std::vector<KeyPair> brute_pairs(const DiscStore& s, const Domain& d, double skin) {
  std::vector<KeyPair> out;
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t j = i + 1; j < s.size(); ++j) {
      if (i >= s.n_owned() && j >= s.n_owned()) continue;
      const Vec2 r = min_image(d, s.position[i], s.position[j]);
      const double reach = s.radius[i] + s.radius[j] + skin;
      if (std::sqrt(dot(r, r)) < reach) out.emplace_back(std::min(s.gid[i], s.gid[j]), std::max(s.gid[i], s.gid[j]));
    }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<KeyPair> keys_of(const ContactTable& t) {
  std::vector<KeyPair> out;
  for (const auto& k : t.key) out.emplace_back(k.lo, k.hi);
  return out;
}

// Empty when equal; otherwise the first few keys missing from / extra in `found`.
std::string difference(const std::vector<KeyPair>& expected, std::vector<KeyPair> found) {
  std::sort(found.begin(), found.end());
  std::vector<KeyPair> missing, extra;
  std::set_difference(expected.begin(), expected.end(), found.begin(), found.end(), std::back_inserter(missing));
  std::set_difference(found.begin(), found.end(), expected.begin(), expected.end(), std::back_inserter(extra));
  if (missing.empty() && extra.empty()) return "";
  std::ostringstream m;
  m << missing.size() << " missing, " << extra.size() << " extra;";
  for (std::size_t k = 0; k < std::min<std::size_t>(5, missing.size()); ++k)
    m << " missing (" << missing[k].first << "," << missing[k].second << ")";
  for (std::size_t k = 0; k < std::min<std::size_t>(5, extra.size()); ++k)
    m << " extra (" << extra[k].first << "," << extra[k].second << ")";
  return m.str();
}

// Rows strictly ascending, indices consistent with the keys, never two ghosts.
void expect_pair_rows_consistent(const ContactTable& t, const DiscStore& s) {
  for (std::size_t r = 0; r < t.size(); ++r) {
    if (r > 0) {
      EXPECT_TRUE(t.key[r - 1] < t.key[r]) << "row " << r << " is not above row " << r - 1;
    }
    const auto i = static_cast<std::size_t>(t.i1[r]), j = static_cast<std::size_t>(t.i2[r]);
    ASSERT_LT(i, s.size());
    ASSERT_LT(j, s.size());
    EXPECT_LT(t.key[r].lo, t.key[r].hi);
    EXPECT_EQ(s.gid[i], t.key[r].lo) << "row " << r;
    EXPECT_EQ(s.gid[j], t.key[r].hi) << "row " << r;
    EXPECT_FALSE(i >= s.n_owned() && j >= s.n_owned()) << "row " << r << " joins two ghosts";
    EXPECT_EQ(t.param[r], 0);
  }
}

struct Built {
  ContactTable pairs{{"xi"}, 0}, walls{{"xi"}, 0, true};
};

Built build_once(NeighbourList& nl, const DiscStore& s, const Domain& d, WallSet& walls) {
  const ContactParamTable params(1);
  Built b;
  nl.build(s, d, walls, params, b.pairs, b.walls);
  return b;
}

void check_against_brute_force(const Domain& d, std::size_t n, double R_min, double R_max, double skin,
                               std::uint64_t seed) {
  const DiscStore s = make_store(random_discs(d, n, R_min, R_max, seed));
  NeighbourList nl(skin);
  WallSet no_walls;
  const Built b = build_once(nl, s, d, no_walls);
  const auto expected = brute_pairs(s, d, skin);
  ASSERT_GT(expected.size(), s.size() / 2) << "the scene is too sparse to test anything";
  EXPECT_EQ(difference(expected, keys_of(b.pairs)), "");
  EXPECT_EQ(b.pairs.size(), expected.size());
  expect_pair_rows_consistent(b.pairs, s);
  EXPECT_EQ(b.walls.size(), 0u);
  EXPECT_EQ(nl.builds(), 1u);
}

Domain box(double xlo, double xhi, double ylo, double yhi, bool px, bool py) {
  Domain d;
  d.xlo = xlo, d.xhi = xhi, d.ylo = ylo, d.yhi = yhi;
  d.periodic_x = px, d.periodic_y = py;
  return d;
}

TEST(NeighbourList, MatchesBruteForceInANonPeriodicBox) {
  check_against_brute_force(box(-0.1, 0.2, 0.05, 0.25, false, false), 700, 0.003, 0.006, 0.0015, 1);
}

TEST(NeighbourList, MatchesBruteForcePeriodicInX) {
  check_against_brute_force(box(0.0, 0.3, 0.0, 0.2, true, false), 700, 0.003, 0.006, 0.0015, 2);
}

TEST(NeighbourList, MatchesBruteForcePeriodicInXAndY) {
  check_against_brute_force(box(-0.15, 0.15, 1.0, 1.2, true, true), 700, 0.003, 0.006, 0.0015, 3);
}

TEST(NeighbourList, MatchesBruteForcePeriodicInYOnly) {
  check_against_brute_force(box(0.0, 0.2, 0.0, 0.3, false, true), 700, 0.003, 0.006, 0.0015, 4);
}

TEST(NeighbourList, MatchesBruteForceWithRadiusRatioThirty) {
  // Cells are sized by the largest disc; small discs next to big ones in neighbouring cells must be found.
  for (bool periodic : {false, true}) {
    SCOPED_TRACE(periodic ? "periodic" : "walled");
    check_against_brute_force(box(0.0, 0.4, 0.0, 0.3, periodic, periodic), 900, 0.0005, 0.015, 0.0004,
                              periodic ? 5 : 6);
  }
}

TEST(NeighbourList, MatchesBruteForceWithTwoAndThreeCellsPerPeriodicDirection) {
  // range = 2 R_max + skin; the periodic stencil wraps onto the same cell and must not double-count.
  const double R = 0.005, skin = 0.001, range = 2 * R + skin;
  for (double cells : {2.0, 2.5, 3.0}) {
    SCOPED_TRACE(cells);
    check_against_brute_force(box(0.0, cells * range, 0.0, cells * range, true, true), 60, R / 2, R, skin,
                              static_cast<std::uint64_t>(10 * cells));
  }
}

TEST(NeighbourList, GapJustBelowSkinIsACandidateJustAboveIsNot) {
  const Domain d = box(0.0, 0.1, 0.0, 0.1, true, false);
  const double R = 0.004, skin = 0.001;
  DiscStore s;
  // Across the periodic seam: gap 0.999 skin (candidate) and 1.001 skin (not).
  s.add(1, 0, R, kDensity, 1, {0.002, 0.02});
  s.add(2, 0, R, kDensity, 1, {0.002 - 2 * R - 0.999 * skin + 0.1, 0.02});
  s.add(3, 0, R, kDensity, 1, {0.002, 0.06});
  s.add(4, 0, R, kDensity, 1, {0.002 - 2 * R - 1.001 * skin + 0.1, 0.06});
  // Inside the box, vertically.
  s.add(5, 0, R, kDensity, 1, {0.05, 0.03});
  s.add(6, 0, R, kDensity, 1, {0.05, 0.03 + 2 * R + 0.999 * skin});
  s.add(7, 0, R, kDensity, 1, {0.05, 0.07});
  s.add(8, 0, R, kDensity, 1, {0.05, 0.07 + 2 * R + 1.001 * skin});
  NeighbourList nl(skin);
  WallSet none;
  const Built b = build_once(nl, s, d, none);
  EXPECT_EQ(keys_of(b.pairs), (std::vector<KeyPair>{{1, 2}, {5, 6}}));
}

TEST(NeighbourList, GhostPairsAreLeftOutAndOwnedGhostPairsKept) {
  // Owned discs on the left half, ghosts (copies of a neighbour rank's discs) on the right half,
  // periodic in x so ghosts also meet owned discs across the seam.
  const Domain d = box(0.0, 0.2, 0.0, 0.1, true, false);
  SceneRandom rng(21);
  DiscStore s;
  std::int64_t gid = 0;
  for (int k = 0; k < 250; ++k)
    s.add(gid += 2, 0, uniform(rng, 0.002, 0.004), kDensity, 1, {uniform(rng, 0.0, 0.1), uniform(rng, 0.0, 0.1)});
  for (int k = 0; k < 250; ++k)
    add_ghost(s, gid += 3, uniform(rng, 0.002, 0.004),
              {uniform(rng, 0.1, std::nextafter(0.2, 0.0)), uniform(rng, 0.0, 0.1)});
  ASSERT_EQ(s.n_owned(), 250u);
  ASSERT_EQ(s.n_ghost(), 250u);
  const double skin = 0.001;
  NeighbourList nl(skin);
  WallSet walls{Wall{}};
  walls[0].p0 = {0.0, 0.0}, walls[0].normal = {0.0, 1.0};
  const Built b = build_once(nl, s, d, walls);
  const auto expected = brute_pairs(s, d, skin);
  EXPECT_EQ(difference(expected, keys_of(b.pairs)), "");
  expect_pair_rows_consistent(b.pairs, s);
  std::size_t owned_ghost = 0;
  auto ghost = [&](std::int32_t i) { return static_cast<std::size_t>(i) >= s.n_owned(); };
  for (std::size_t r = 0; r < b.pairs.size(); ++r) owned_ghost += ghost(b.pairs.i1[r]) != ghost(b.pairs.i2[r]);
  EXPECT_GT(owned_ghost, 10u) << "the scene should have owned-ghost pairs on both seams";
  for (std::size_t r = 0; r < b.walls.size(); ++r)
    EXPECT_LT(static_cast<std::size_t>(b.walls.i1[r]), s.n_owned()) << "wall row " << r << " is for a ghost";
  EXPECT_GT(b.walls.size(), 5u);
}

TEST(NeighbourList, RowsAscendWhenOwnedDiscsAreOutOfGidOrderAndGhostGidsLieBetweenThem) {
  // The rows come out in key order without a sort of the list (owned discs visited in gid order, ghosts merged
  // in): here the owned discs are stored in a shuffled gid order and the ghosts' gids interleave with theirs.
  const Domain d = box(0.0, 0.2, 0.0, 0.1, true, false);
  SceneRandom rng(5);
  std::vector<std::int64_t> gids(500);
  for (std::size_t k = 0; k < gids.size(); ++k) gids[k] = static_cast<std::int64_t>(7 * k + 1);
  for (std::size_t k = gids.size() - 1; k > 0; --k)  // Fisher-Yates with the scene generator
    std::swap(gids[k], gids[static_cast<std::size_t>(uniform(rng, 0.0, static_cast<double>(k + 1))) % (k + 1)]);
  DiscStore s;
  for (int k = 0; k < 250; ++k)
    s.add(gids[static_cast<std::size_t>(k)], 0, uniform(rng, 0.002, 0.004), kDensity, 1,
          {uniform(rng, 0.0, 0.1), uniform(rng, 0.0, 0.1)});
  for (int k = 250; k < 500; ++k)
    add_ghost(s, gids[static_cast<std::size_t>(k)], uniform(rng, 0.002, 0.004),
              {uniform(rng, 0.1, std::nextafter(0.2, 0.0)), uniform(rng, 0.0, 0.1)});
  ASSERT_FALSE(std::is_sorted(s.gid.begin(), s.gid.begin() + 250));
  const double skin = 0.001;
  NeighbourList nl(skin);
  WallSet no_walls;
  const Built b = build_once(nl, s, d, no_walls);
  const auto expected = brute_pairs(s, d, skin);
  ASSERT_GT(expected.size(), 200u);
  EXPECT_EQ(difference(expected, keys_of(b.pairs)), "");
  expect_pair_rows_consistent(b.pairs, s);  // strictly ascending keys
  std::size_t ghost_lower = 0;              // rows whose lower gid is a ghost's: merged between the owned discs' rows
  for (std::size_t r = 0; r < b.pairs.size(); ++r)
    ghost_lower += static_cast<std::size_t>(b.pairs.i1[r]) >= s.n_owned();
  EXPECT_GT(ghost_lower, 10u);
}

// Independent distances: signed for a line (along its unit normal), Euclidean to the closest point of a
// segment.
double wall_distance(const Wall& w, Vec2 x) {
  if (w.kind == Wall::Kind::line) return (x.x - w.p0.x) * w.normal.x + (x.y - w.p0.y) * w.normal.y;
  const double ex = w.p1.x - w.p0.x, ey = w.p1.y - w.p0.y;
  const double s = std::clamp(((x.x - w.p0.x) * ex + (x.y - w.p0.y) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
  return std::hypot(w.p0.x + s * ex - x.x, w.p0.y + s * ey - x.y);
}

TEST(NeighbourList, WallRowsMatchBruteForceForLinesAndSegments) {
  const Domain d = box(0.0, 0.2, 0.0, 0.2, false, false);
  const double skin = 0.001;
  WallSet walls(3);
  walls[0].kind = Wall::Kind::line, walls[0].p0 = {0.0, 0.0}, walls[0].normal = {0.0, 1.0};
  const double s2 = std::sqrt(0.5);
  walls[1].kind = Wall::Kind::line, walls[1].p0 = {0.2, 0.15}, walls[1].normal = {-s2, -s2};
  walls[2].kind = Wall::Kind::segment, walls[2].p0 = {0.05, 0.1}, walls[2].p1 = {0.12, 0.13};
  const DiscStore s = make_store(random_discs(d, 600, 0.002, 0.005, 31));
  NeighbourList nl(skin);
  const Built b = build_once(nl, s, d, walls);

  std::vector<KeyPair> expected;
  std::size_t per_wall[3] = {0, 0, 0};
  for (std::size_t i = 0; i < s.size(); ++i)
    for (std::size_t w = 0; w < walls.size(); ++w)
      if (wall_distance(walls[w], s.position[i]) < s.radius[i] + skin) {
        expected.emplace_back(s.gid[i], static_cast<std::int64_t>(w));
        ++per_wall[w];
      }
  std::sort(expected.begin(), expected.end());
  for (std::size_t w = 0; w < 3; ++w) EXPECT_GT(per_wall[w], 3u) << "wall " << w << " has too few candidates";
  EXPECT_EQ(difference(expected, keys_of(b.walls)), "");
  EXPECT_EQ(b.walls.size(), expected.size());
  for (std::size_t r = 0; r < b.walls.size(); ++r) {
    if (r > 0) {
      EXPECT_TRUE(b.walls.key[r - 1] < b.walls.key[r]) << "wall row " << r;
    }
    EXPECT_EQ(s.gid[static_cast<std::size_t>(b.walls.i1[r])], b.walls.key[r].lo);
    EXPECT_EQ(b.walls.i2[r], b.walls.key[r].hi);
  }
}

TEST(NeighbourList, WallRowAppearsOnlyWithinRadiusPlusSkin) {
  const Domain d = box(0.0, 1.0, 0.0, 1.0, false, false);
  const double R = 0.01, skin = 0.002;
  WallSet walls(2);
  walls[0].kind = Wall::Kind::line, walls[0].p0 = {0.0, 0.0}, walls[0].normal = {0.0, 1.0};
  walls[1].kind = Wall::Kind::segment, walls[1].p0 = {0.5, 0.5}, walls[1].p1 = {0.6, 0.5};
  DiscStore s;
  s.add(1, 0, R, kDensity, 1, {0.2, R + 0.99 * skin});         // line: in
  s.add(2, 0, R, kDensity, 1, {0.3, R + 1.01 * skin});         // line: out
  s.add(3, 0, R, kDensity, 1, {0.6 + R + 0.99 * skin, 0.5});   // beyond the segment's end: in
  s.add(4, 0, R, kDensity, 1, {0.5 - R - 1.01 * skin, 0.5});   // beyond the other end: out
  s.add(5, 0, R, kDensity, 1, {0.55, 0.5 - R - 0.99 * skin});  // below the segment: in
  NeighbourList nl(skin);
  const Built b = build_once(nl, s, d, walls);
  EXPECT_EQ(keys_of(b.walls), (std::vector<KeyPair>{{1, 0}, {3, 1}, {5, 1}}));
}

double tag(ContactKey k) { return static_cast<double>(k.lo) * 1.0e5 + static_cast<double>(k.hi) + 0.25; }

TEST(NeighbourList, HistoryFollowsItsKeyAcrossARebuildWithPermutedStorage) {
  const Domain d = box(0.0, 0.25, 0.0, 0.2, true, false);
  const double skin = 0.0015;
  auto discs = random_discs(d, 600, 0.003, 0.006, 41);
  WallSet walls(1);
  walls[0].kind = Wall::Kind::line, walls[0].p0 = {0.0, 0.0}, walls[0].normal = {0.0, 1.0};
  NeighbourList nl(skin);
  const ContactParamTable params(1);
  const DiscStore first = make_store(discs);
  const Built old = [&] {
    Built b = build_once(nl, first, d, walls);
    for (std::size_t r = 0; r < b.pairs.size(); ++r) b.pairs.slot[0][r] = b.pairs.F_n[r] = tag(b.pairs.key[r]);
    for (std::size_t r = 0; r < b.walls.size(); ++r) b.walls.slot[0][r] = b.walls.F_n[r] = -tag(b.walls.key[r]);
    return b;
  }();

  // Small moves (up to 0.45 skin each), then a different storage order.
  SceneRandom rng(42);
  for (auto& p : discs) {
    p.x += Vec2{uniform(rng, -0.45, 0.45) * skin, uniform(rng, -0.45, 0.45) * skin};
    d.wrap(p.x);
  }
  for (std::size_t k = discs.size(); k > 1; --k) std::swap(discs[k - 1], discs[rng.next() % k]);
  const DiscStore second = make_store(discs);
  Built now = old;  // the history source: build() replaces the rows it holds
  nl.build(second, d, walls, params, now.pairs, now.walls);
  EXPECT_EQ(difference(brute_pairs(second, d, skin), keys_of(now.pairs)), "");
  expect_pair_rows_consistent(now.pairs, second);

  std::map<KeyPair, double> before;
  for (const auto& k : old.pairs.key) before[{k.lo, k.hi}] = tag(k);
  std::size_t kept = 0, fresh = 0;
  for (std::size_t r = 0; r < now.pairs.size(); ++r) {
    const ContactKey k = now.pairs.key[r];
    const auto it = before.find({k.lo, k.hi});
    const double want = it == before.end() ? 0.0 : it->second;
    (it == before.end() ? fresh : kept) += 1;
    EXPECT_EQ(now.pairs.slot[0][r], want) << "pair (" << k.lo << "," << k.hi << ")";
    EXPECT_EQ(now.pairs.F_n[r], want) << "pair (" << k.lo << "," << k.hi << ")";
  }
  const std::size_t dropped = old.pairs.size() - kept;
  EXPECT_GT(kept, 100u);
  EXPECT_GT(fresh, 0u) << "the moves should create new candidates";
  EXPECT_GT(dropped, 0u) << "the moves should drop old candidates";

  std::map<KeyPair, double> wall_before;
  for (const auto& k : old.walls.key) wall_before[{k.lo, k.hi}] = -tag(k);
  std::size_t wall_kept = 0;
  for (std::size_t r = 0; r < now.walls.size(); ++r) {
    const ContactKey k = now.walls.key[r];
    const auto it = wall_before.find({k.lo, k.hi});
    wall_kept += it != wall_before.end();
    EXPECT_EQ(now.walls.slot[0][r], it == wall_before.end() ? 0.0 : it->second)
        << "wall row (" << k.lo << "," << k.hi << ")";
    EXPECT_EQ(second.gid[static_cast<std::size_t>(now.walls.i1[r])], k.lo);
  }
  EXPECT_GT(wall_kept, 5u);
}

TEST(NeighbourList, RebuildIsDueAfterHalfTheSkin) {
  const Domain d = box(0.0, 1.0, 0.0, 1.0, true, false);
  const double skin = 0x1.0p-8;  // exact halves and sums below
  DiscStore s;
  s.add(1, 0, 0.01, kDensity, 1, {0.25, 0.5});
  s.add(2, 0, 0.01, kDensity, 1, {0.75, 0.5});
  s.add(3, 0, 0.01, kDensity, 1, {1.0 - 0x1.0p-10, 0.25});  // by the periodic seam
  NeighbourList nl(skin);
  WallSet walls;
  EXPECT_TRUE(std::isinf(nl.max_displacement(s, d))) << "no build yet";
  EXPECT_TRUE(nl.needs_rebuild(nl.max_displacement(s, d), walls));
  build_once(nl, s, d, walls);
  EXPECT_EQ(nl.max_displacement(s, d), 0.0);
  EXPECT_FALSE(nl.needs_rebuild(0.0, walls));

  s.position[0].x += 0.5 * skin;
  EXPECT_EQ(nl.max_displacement(s, d), 0.5 * skin);
  EXPECT_FALSE(nl.needs_rebuild(nl.max_displacement(s, d), walls)) << "exactly half the skin is still safe";
  s.position[0].x += 0x1.0p-30;
  EXPECT_TRUE(nl.needs_rebuild(nl.max_displacement(s, d), walls));
  EXPECT_TRUE(nl.needs_rebuild(NAN, walls));

  // A move across the periodic seam counts by its minimum image.
  build_once(nl, s, d, walls);
  s.position[2].x += 0.25 * skin;
  d.wrap(s.position[2]);
  ASSERT_LT(s.position[2].x, 0.5);
  EXPECT_NEAR(nl.max_displacement(s, d), 0.25 * skin, 1e-15);
  EXPECT_FALSE(nl.needs_rebuild(nl.max_displacement(s, d), walls));
}

TEST(NeighbourList, WallMotionAddsToDiscMotion) {
  const double skin = 0x1.0p-8;
  NeighbourList nl(skin);
  WallSet walls(2);
  walls[0].normal = {0.0, 1.0};
  walls[1].normal = {1.0, 0.0};
  walls[1].displacement_since_build = {0.0, 0.25 * skin};
  walls[0].displacement_since_build = {0.5 * skin, 0.0};
  EXPECT_FALSE(nl.needs_rebuild(0.5 * skin, walls)) << "disc 0.5 + wall 0.5 = the skin";
  EXPECT_TRUE(nl.needs_rebuild(0.5 * skin + 0x1.0p-30, walls));
  walls[0].displacement_since_build = {0.0, 0.75 * skin};
  EXPECT_FALSE(nl.needs_rebuild(0.25 * skin, walls));
  EXPECT_TRUE(nl.needs_rebuild(0.3 * skin, walls));
  walls[0].displacement_since_build = {1.01 * skin, 0.0};
  EXPECT_TRUE(nl.needs_rebuild(0.0, walls)) << "a wall alone past the skin";

  // A build resets every wall's displacement.
  walls[0].velocity = {1.0, 0.0};
  walls[0].move(0.5 * skin);
  DiscStore s;
  s.add(1, 0, 0.01, kDensity, 1, {0.5, 0.5});
  build_once(nl, s, Domain{}, walls);
  for (const auto& w : walls) EXPECT_EQ(dot(w.displacement_since_build, w.displacement_since_build), 0.0);
  EXPECT_FALSE(nl.needs_rebuild(0.5 * skin, walls));
}

// The step's check: a bound that grows by each drift's largest step and is replaced by the exact largest
// displacement once it passes half the skin, so a rebuild is decided on the exact value; a rough wall's
// displacement stands for its glued discs'.
TEST(NeighbourList, DisplacementBoundGrowsByStepsAndIsExactPastHalfTheSkin) {
  const Domain d = box(0.0, 1.0, 0.0, 1.0, false, false);
  const double skin = 0x1.0p-8;  // exact halves and sums below
  DiscStore s;
  s.add(1, 0, 0.01, kDensity, 1, {0.25, 0.5});
  s.add(2, 0, 0.01, kDensity, 1, {0.75, 0.5});
  NeighbourList nl(skin);
  WallSet walls;
  EXPECT_TRUE(std::isinf(nl.displacement(0.0, s, d, walls))) << "no build yet: the exact value, infinite";
  build_once(nl, s, d, walls);
  // Disc 1 steps forth and back: the bound adds both steps though it is back where it started.
  s.position[0].x += 0.125 * skin;
  EXPECT_EQ(nl.displacement(0.125 * skin, s, d, walls), 0.125 * skin);
  s.position[0].x -= 0.125 * skin;
  EXPECT_EQ(nl.displacement(0.125 * skin, s, d, walls), 0.25 * skin);
  EXPECT_EQ(nl.displacement(0.25 * skin, s, d, walls), 0.5 * skin) << "at half the skin: still the bound";
  // Past half the skin, the exact value: disc 2 has moved by 0.0625 skin since the build.
  s.position[1].y += 0.0625 * skin;
  EXPECT_EQ(nl.displacement(0x1.0p-30, s, d, walls), 0.0625 * skin);
  EXPECT_FALSE(nl.needs_rebuild(nl.displacement(0.0, s, d, walls), walls));
  // A real move past half the skin: exact, and a rebuild is due.
  s.position[1].y += 0.5 * skin;
  EXPECT_EQ(nl.displacement(0.5 * skin, s, d, walls), 0.5625 * skin);
  EXPECT_TRUE(nl.needs_rebuild(nl.displacement(0.0, s, d, walls), walls));
  EXPECT_EQ(nl.displacement(NAN, s, d, walls), 0.5625 * skin) << "a NaN step asks for the exact value";
  // Glued discs move with their rough wall.
  build_once(nl, s, d, walls);
  walls.resize(1);
  walls[0].normal = {0.0, 1.0};
  walls[0].displacement_since_build = {0.0, 0.375 * skin};
  EXPECT_EQ(nl.displacement(0.0, s, d, walls), 0.0) << "a smooth wall moves no disc";
  walls[0].rough = true;
  EXPECT_EQ(nl.displacement(0.0, s, d, walls), 0.375 * skin);
}

TEST(NeighbourList, MovingAGhostDoesNotCountAsDisplacement) {
  const Domain d = box(0.0, 1.0, 0.0, 1.0, false, false);
  DiscStore s;
  s.add(1, 0, 0.01, kDensity, 1, {0.25, 0.5});
  add_ghost(s, 2, 0.01, {0.75, 0.5});
  const double skin = 0.004;
  NeighbourList nl(skin);
  WallSet walls;
  build_once(nl, s, d, walls);
  s.position[1].x += 10 * skin;
  EXPECT_EQ(nl.max_displacement(s, d), 0.0);
}

}  // namespace
}  // namespace rondel
