// Ghosts (docs/design.md section 6): on every rank, after construction and after steps, the ghost set is the
// set the halo rule gives by brute force over the whole scene, every disc within interaction range of an
// owned disc is present locally (minimum image), and every ghost is a bit copy of its owner.
//
// The halo rule of src/parallel/DiscExchange.cpp (build_ghosts): at a rebuild, a disc is a ghost on rank r
// iff r owns one of the 3 x 3 stencil cells around the disc's cell (periodic wrap) and r is not the owner
// of the disc's cell. Between rebuilds the ghost set stays; positions, velocities and spins are refreshed
// after the drift (update_ghosts), so at the end of a step a ghost holds its owner's position and the
// owner's half-step velocity and spin: kicking the ghost's v and omega with the owner's force and torque
// (the arithmetic of Integrator::half_kick) must give the owner's bits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {
namespace {

using namespace partest;

// One owned disc as every rank sees it after an all-gather.
struct Rec {
  std::int64_t gid;
  std::int32_t material;
  std::uint32_t flags;
  double x, y, vx, vy, omega, radius, mass, inertia, fx, fy, torque;
};

Rec record(const DiscStore& d, std::size_t i) {
  return Rec{d.gid[i],   d.material[i], d.flags[i], d.position[i].x, d.position[i].y, d.velocity[i].x, d.velocity[i].y,
             d.omega[i], d.radius[i],   d.mass[i],  d.inertia[i],    d.force[i].x,    d.force[i].y,    d.torque[i]};
}

// Every owned disc of every rank, by gid, with the rank that stores it (collective).
struct Global {
  std::map<std::int64_t, Rec> disc;
  std::map<std::int64_t, int> rank;
};

Global gather_all(const Simulation& sim) {
  std::string mine;
  for (std::size_t i = 0; i < sim.discs().n_owned(); ++i) {
    const Rec r = record(sim.discs(), i);
    mine.append(reinterpret_cast<const char*>(&r), sizeof r);
  }
  Global g;
  const auto all = all_gather(mine);
  for (std::size_t k = 0; k < all.size(); ++k)
    for (std::size_t off = 0; off + sizeof(Rec) <= all[k].size(); off += sizeof(Rec)) {
      Rec r;
      std::memcpy(&r, all[k].data() + off, sizeof r);
      const bool dup = g.disc.count(r.gid) > 0;
      EXPECT_FALSE(dup) << "disc " << r.gid << " owned by ranks " << g.rank[r.gid] << " and " << k;
      g.disc[r.gid] = r;
      g.rank[r.gid] = static_cast<int>(k);
    }
  return g;
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// The snapshot of the last rebuild: positions and cell map then, and the ghost set they give here.
struct Halo {
  std::set<std::int64_t> ghosts;
  bool valid = false;
};

class GhostChecker {
 public:
  GhostChecker(const Simulation& sim, std::size_t total) : sim_(sim), total_(total) {
    double R_sum = 0.0;
    for (const auto& [gid, r] : gather_all(sim).disc) R_max_ = std::max(R_max_, r.radius), R_sum += r.radius;
    skin_ = sim.config().skin > 0.0 ? sim.config().skin : 0.25 * R_sum / static_cast<double>(total);
  }

  // Checks the rank's discs against the whole scene; `rebuilt`: a rebuild made the present ghost set;
  // `map_fresh`: with the present cell map (no repartition since); `at_start`: no kick since the ghosts
  // were made (velocities equal the owners'). Returns the number of problems on this rank (messages in
  // `log`).
  int check(bool rebuilt, bool map_fresh, bool at_start, std::string& log) {
    const Global g = gather_all(sim_);
    const DiscStore& d = sim_.discs();
    const Decomposition& dec = sim_.decomposition();
    const Domain& dom = sim_.config().domain;
    const int me = world_rank();
    int bad = 0;
    auto fail = [&](const std::string& m) {
      if (++bad <= 5)
        log += "rank " + std::to_string(me) + " step " + std::to_string(sim_.step_count()) + ": " + m + "\n";
    };
    if (g.disc.size() != total_)
      fail("the ranks own " + std::to_string(g.disc.size()) + " discs, not " + std::to_string(total_));
    std::set<std::int64_t> owned, ghosts;
    for (std::size_t i = 0; i < d.n_owned(); ++i) owned.insert(d.gid[i]);
    for (std::size_t i = d.n_owned(); i < d.size(); ++i)
      if (!ghosts.insert(d.gid[i]).second) fail("ghost " + std::to_string(d.gid[i]) + " twice");
    if (ghosts.size() != sim_.state().ghosts)
      fail("ghost_count() = " + std::to_string(sim_.state().ghosts) + " but " + std::to_string(ghosts.size()) +
           " ghosts stored");
    for (std::int64_t gid : ghosts)
      if (owned.count(gid)) fail("disc " + std::to_string(gid) + " is owned and a ghost");

    // The halo rule at the rebuild (positions now = positions at the rebuild).
    if (rebuilt && !map_fresh) {
      halo_.valid = false;  // made with a map that has been replaced since: nothing to compare with
    } else if (rebuilt) {
      std::set<std::int64_t> expect;
      for (const auto& [gid, r] : g.disc) {
        const std::size_t cell = dec.grid().cell_of({r.x, r.y});
        const int owner = dec.owner_of_cell(cell);
        if (owner == me && g.rank.at(gid) != me)
          fail("disc " + std::to_string(gid) + " lies in a cell of this rank but is stored on rank " +
               std::to_string(g.rank.at(gid)));
        if (owner == me) continue;
        for (std::size_t c : dec.grid().stencil(cell))
          if (dec.owner_of_cell(c) == me) expect.insert(gid);
      }
      if (expect != ghosts) {
        std::string m = "ghost set differs from the halo rule:";
        int shown = 0;
        for (std::int64_t gid : expect)
          if (!ghosts.count(gid) && shown++ < 5) m += " missing " + std::to_string(gid);
        for (std::int64_t gid : ghosts)
          if (!expect.count(gid) && shown++ < 10) m += " extra " + std::to_string(gid);
        fail(m + " (" + std::to_string(expect.size()) + " expected, " + std::to_string(ghosts.size()) + " present)");
      }
      halo_.ghosts = ghosts;
      halo_.valid = true;
    } else if (halo_.valid && ghosts != halo_.ghosts) {
      fail("the ghost set changed without a rebuild");
    }

    // Physical requirement: every disc within range of an owned disc is here. At a rebuild the range is
    // the interaction range 2 R_max + skin; between rebuilds, every disc touching an owned disc.
    const double range = 2 * R_max_ + skin_;
    for (std::size_t i = 0; i < d.n_owned(); ++i)
      for (const auto& [gid, r] : g.disc) {
        if (gid == d.gid[i] || owned.count(gid) || ghosts.count(gid)) continue;
        const Vec2 s = dom.separation(d.position[i], {r.x, r.y});
        const double reach = rebuilt ? range : d.radius[i] + r.radius;
        if (dot(s, s) < reach * reach)
          fail("disc " + std::to_string(gid) + " at distance " + std::to_string(std::sqrt(dot(s, s))) +
               " of owned disc " + std::to_string(d.gid[i]) + " is missing (reach " + std::to_string(reach) + ")");
      }

    // Ghosts are bit copies of their owners.
    const double h = 0.5 * sim_.dt();
    for (std::size_t i = d.n_owned(); i < d.size(); ++i) {
      const auto it = g.disc.find(d.gid[i]);
      if (it == g.disc.end()) {
        fail("ghost " + std::to_string(d.gid[i]) + " has no owner");
        continue;
      }
      const Rec& o = it->second;
      const std::string who =
          "ghost " + std::to_string(d.gid[i]) + " (owner rank " + std::to_string(g.rank.at(d.gid[i])) + ")";
      if (!same_bits(d.position[i].x, o.x) || !same_bits(d.position[i].y, o.y))
        fail(who + ": position is not the owner's bits");
      if (!same_bits(d.radius[i], o.radius) || !same_bits(d.mass[i], o.mass) || !same_bits(d.inertia[i], o.inertia) ||
          d.flags[i] != o.flags || d.material[i] != o.material)
        fail(who + ": radius, mass, inertia, flags or material differ");
      double vx = d.velocity[i].x, vy = d.velocity[i].y, w = d.omega[i];
      if (!at_start && !(o.flags & kFlagFixed)) {
        vx += h * o.fx / o.mass;
        vy += h * o.fy / o.mass;
        w += h * o.torque / o.inertia;
      }
      if (!same_bits(vx, o.vx) || !same_bits(vy, o.vy) || !same_bits(w, o.omega))
        fail(who + ": velocity or spin is not the owner's bits" + (at_start ? "" : " (after the owner's half kick)"));
    }
    return bad;
  }

 private:
  const Simulation& sim_;
  std::size_t total_;
  double R_max_ = 0.0, skin_ = 0.0;
  Halo halo_;
};

// Collective verdict: rank 0 reports every rank's messages.
void report(int bad, const std::string& log, const std::string& what) {
  const bool ok = all_ranks(bad == 0);
  const auto logs = gather(log);
  if (world_rank() == 0 && !ok) {
    std::string all;
    for (const auto& l : logs) all += l;
    ADD_FAILURE() << what << ":\n" << all;
  }
}

void check_ghosts(const std::string& scene, const std::string& ini, const std::vector<std::string>& overrides,
                  int steps, int min_rebuild_checks = 3) {
  static const Communicator world(MPI_COMM_WORLD);
  const Config cfg = parse_config_text(ini, overrides);
  // The whole scene, rebuilt independently of the run.
  const auto all = build_scene(SceneInputs{cfg.scene, cfg.domain, ""});
  Simulation sim(cfg, world, false);
  {
    // The ranks together own exactly the scene's discs, at the scene's (wrapped) positions.
    const Global g = gather_all(sim);
    int bad = 0;
    std::string log;
    for (const SceneDisc& s : all) {
      Vec2 x = s.x;
      cfg.domain.wrap(x);
      const auto it = g.disc.find(s.gid);
      if (it == g.disc.end() || !same_bits(it->second.x, x.x) || !same_bits(it->second.y, x.y) ||
          !same_bits(it->second.radius, s.radius))
        if (++bad <= 5) log += "scene disc " + std::to_string(s.gid) + " missing or moved after distribution\n";
    }
    if (g.disc.size() != all.size()) ++bad, log += "owned discs " + std::to_string(g.disc.size()) + " != scene size\n";
    report(world_rank() == 0 ? bad : 0, world_rank() == 0 ? log : "", scene + ": distribution");
  }
  GhostChecker checker(sim, all.size());
  std::string log;
  int bad = checker.check(true, true, true, log);
  report(bad, log, scene + ": after construction");
  const std::int64_t every = sim.config().balance_every;
  std::size_t builds = sim.counts().neighbour_builds;
  int rebuild_checks = 0, other_checks = 0;
  std::size_t ghosts_max = 0, ghosts_min = SIZE_MAX;
  for (int s = 0; s < steps; ++s) {
    sim.step();
    const bool rebuilt = sim.counts().neighbour_builds != builds;
    builds = sim.counts().neighbour_builds;
    // A balance check at the end of this step may have changed the map after the rebuild: skip the
    // halo rule then (the next step rebuilds with the new map).
    const bool map_fresh =
        !(every > 0 && sim.step_count() % every == 0 && sim.config().partitioner == "metis" && world_size() > 1);
    if (!(rebuilt || s % 25 == 0)) continue;
    log.clear();
    bad = checker.check(rebuilt, map_fresh, false, log);
    report(bad, log, scene + ": step " + std::to_string(sim.step_count()));
    ++(rebuilt && map_fresh ? rebuild_checks : other_checks);
    ghosts_max = std::max(ghosts_max, sim.state().ghosts);
    ghosts_min = std::min(ghosts_min, sim.state().ghosts);
  }
  const auto migrated = sim.diagnostics().migrated;
  if (world_rank() == 0)
    std::cout << "[ ghosts   ] " << scene << " on " << world_size() << " ranks: " << rebuild_checks
              << " checks at rebuilds, " << other_checks << " between; rank 0 held " << ghosts_min << " to "
              << ghosts_max << " ghosts; " << migrated << " discs migrated\n";
  EXPECT_GE(rebuild_checks, min_rebuild_checks) << scene;
  if (world_size() > 1) {
    if (min_rebuild_checks > 0) {
      EXPECT_GT(migrated, 0) << scene;
    }
    EXPECT_TRUE(all_ranks(sim.state().ghosts > 0)) << scene << ": a rank holds no ghost";
  } else {
    EXPECT_EQ(sim.state().ghosts, 0u);
  }
}

TEST(Ghosts, PeriodicPackingGrid) {
  check_ghosts("periodic / grid", periodic_ini(), {"--parallel.partitioner=grid"}, 800);
}

TEST(Ghosts, PeriodicPackingMetisRebalanced) {
  check_ghosts("periodic / metis+rebalance/7", periodic_ini(),
               {"--parallel.partitioner=metis", "--parallel.force_balance=true", "--parallel.balance_every=7"}, 800);
}

TEST(Ghosts, DepositionMetisRebalanced) {
  check_ghosts("deposition / metis+rebalance/7", deposition_ini(),
               {"--parallel.partitioner=metis", "--parallel.force_balance=true", "--parallel.balance_every=7"}, 1500);
}

// A periodic box of 2 x 2 cells (a skin of 15 mm makes the cells 17 mm wide): every stencil wraps onto
// the same cells from both sides, every disc is a ghost on every other rank that owns a cell, and minimum
// images cross the seams. METIS (the grid blocks cannot split 2 x 2 cells into 3 ranks).
TEST(Ghosts, PeriodicTwoByTwoCells) {
  check_ghosts("periodic / metis / 2 x 2 cells", periodic_ini(),
               {"--parallel.partitioner=metis", "--neighbour.skin=0.015"}, 200, 0);
}

}  // namespace
}  // namespace rondel
