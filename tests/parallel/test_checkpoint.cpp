// Checkpoints and restarts (docs/design.md section 7, FORMAT.md): a run of 2N steps and a run of N steps,
// checkpoint, restart (on another rank count) and N more steps end in the same bits; two checkpoints of one
// step written on different rank counts compare equal with h5diff (run metadata, ledger and the attributes'
// checksum that covers them excluded).
//
// Each mpiexec job (mpi.np1 ... mpi.np4) tests the writer -> restart rank counts of its size, on
// sub-communicators made with MPI_Comm_split (ranks outside one wait at a barrier):
//   np1: 1 -> 1        np2: 2 -> 1, 1 -> 2        np3: 3 -> 1        np4: 1 -> 4, 4 -> 2
// The scene: discs dropped into a box (bottom and right walls) whose left wall is a line moving into the
// pile at 0.4 m/s, with gravity, Coulomb friction and a rolling law that carries history (wang: xi, x_r;
// jiang_plastic: xi, theta_r). At the checkpoint, disc pairs and discs on the moving wall carry history.
//
// The reference is an uninterrupted 2N-step run on rank 0 alone (MPI_COMM_SELF, no files, Simulation::step).
// For each case the writer runs 2N steps through Simulation::run() with output.checkpoint_every = N (it
// must still match the reference: writing a checkpoint changes nothing) and leaves checkpoint_N and
// checkpoint_2N; the restart starts from checkpoint_N, also through run() (run.steps = 2N is the total),
// and ends with its own checkpoint_2N and final.csv. Every writer and restart of a job uses the same
// configuration (the same run.output string), so the stored configuration texts are equal and the files
// can be compared whole with h5diff: the restart's checkpoint_2N must be the writer's (contact rows and
// history included), and checkpoint_N must not depend on the writer's rank count.
#include <gtest/gtest.h>
#include <mpi.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "ParallelTestUtil.hpp"
#include "app/Simulation.hpp"
#include "core/Config.hpp"
#include "parallel/Communicator.hpp"
#include "parallel/Hdf5File.hpp"
#include "parallel/StateFile.hpp"
#include "support/Assertions.hpp"
#include "support/Quiet.hpp"
#include "support/Scenes.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

constexpr int kHalf = 2500;  // N: the checkpoint step; the runs end at 2N

using partest::broadcast;
using partest::SharedTempDir;
using partest::SubComm;
using partest::world_barrier;
using partest::world_rank;
using partest::world_size;
using test::QuietCout;
using test::read_file;

// h5diff of two Rondel files without the run metadata and the ledger (FORMAT.md): "" when equal, else the
// exit status and the first lines of its report. Rank 0 only.
std::string h5diff(const fs::path& a, const fs::path& b, const fs::path& scratch) {
  const fs::path report = scratch / "h5diff.txt";
  const std::string cmd = "h5diff --exclude-path /run_metadata --exclude-path /ledger --exclude-path /integrity '" +
                          a.string() + "' '" + b.string() + "' > '" + report.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  const int code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  if (code == 0) return "";
  std::string text = read_file(report);
  if (text.size() > 1500) text = text.substr(0, 1500) + "...";
  return "h5diff exit " + std::to_string(code) + " (" + a.filename().string() + " vs " + b.filename().string() +
         "):\n" + text;
}

std::string scene_ini(const std::string& law) { return test::moving_wall_box_ini(law, "[diagnostics]\nevery = 500\n"); }

struct Case {
  int writer, restart;
};

std::vector<Case> cases_for(int world) {
  switch (world) {
    case 1:
      return {{1, 1}};
    case 2:
      return {{2, 1}, {1, 2}};
    case 3:
      return {{3, 1}};
    default:
      return {{1, 4}, {4, 2}};
  }
}

// What the checkpoint holds, read back on rank 0 with the file wrapper (MPI_COMM_SELF).
struct CheckpointContent {
  std::int64_t step = -1, complete = 0, ranks = 0;
  std::uint64_t pair_rows = 0, pair_rows_with_history = 0;
  std::uint64_t wall_rows = 0, wall_rows_with_history = 0;
  std::uint64_t moving_wall_rows_with_history = 0;  // rows on the wall with a velocity
  double moving_wall_x = 0.0, moving_wall_y = 0.0;  // its position (every wall here starts at the origin)
  std::vector<std::string> slots;
};

CheckpointContent inspect(const fs::path& path) {
  const Communicator self(MPI_COMM_SELF);
  CheckpointContent c;
  const StateHeader h = read_state_header(path.string(), self);
  c.slots = h.slots;
  Hdf5File f(path.string(), Hdf5File::Mode::read, self);
  c.step = f.read_int_attribute("/", "step");
  c.complete = f.read_int_attribute("/", "complete");
  c.ranks = f.read_int_attribute("/run_metadata", "ranks");
  const std::uint64_t nw = f.rows("/walls/kind");
  const auto velocity = f.read<Vec2>("/walls/velocity", 0, nw);
  const auto p0 = f.read<Vec2>("/walls/p0", 0, nw);
  // A rotating wall (format version 3) moves too.
  const auto omega = f.rows("/walls/omega") == nw ? f.read<double>("/walls/omega", 0, nw) : std::vector<double>(nw);
  std::int64_t moving = -1;
  for (std::uint64_t w = 0; w < nw; ++w)
    if (velocity[w].x != 0.0 || velocity[w].y != 0.0 || omega[w] != 0.0)
      moving = static_cast<std::int64_t>(w), c.moving_wall_x = p0[w].x, c.moving_wall_y = p0[w].y;
  for (const char* group : {"/contacts", "/wall_contacts"}) {
    const std::string g = group;
    const std::uint64_t n = f.rows(g + "/key");
    const auto key = f.read<ContactKey>(g + "/key", 0, n);
    std::vector<bool> loaded(n, false);
    for (const std::string& s : h.slots) {
      const auto v = f.read<double>(g + "/history/" + s, 0, n);
      for (std::uint64_t r = 0; r < n; ++r) loaded[r] = loaded[r] || v[r] != 0.0;
    }
    std::uint64_t with = 0, on_moving = 0;
    for (std::uint64_t r = 0; r < n; ++r) {
      with += loaded[r];
      if (g == "/wall_contacts" && loaded[r] && key[r].hi == moving) ++on_moving;
    }
    if (g == "/contacts")
      c.pair_rows = n, c.pair_rows_with_history = with;
    else
      c.wall_rows = n, c.wall_rows_with_history = with, c.moving_wall_rows_with_history = on_moving;
  }
  return c;
}

void restart_cases(const std::string& law, const std::vector<std::string>& extra = {}) {
  const int W = world_size();
  const bool root = world_rank() == 0;
  SharedTempDir tmp("ckpt-" + law + (extra.empty() ? "" : "-rebalance"));
  const fs::path out = tmp.path() / "run";  // the one run.output of every writer and restart
  std::vector<std::string> overrides{"--run.output=" + out.string(), "--run.overwrite=true",
                                     "--run.steps=" + std::to_string(2 * kHalf),
                                     "--output.checkpoint_every=" + std::to_string(kHalf)};
  overrides.insert(overrides.end(), extra.begin(), extra.end());
  const std::string ini = scene_ini(law);
  auto checkpoint_name = [&](std::int64_t step) { return out / Checkpointing::file_name("checkpoint", step); };

  // The uninterrupted run (rank 0 alone, no files).
  std::string reference;
  if (root) {
    const Communicator self(MPI_COMM_SELF);
    Simulation ref(parse_config_text(ini, overrides), self, false);
    for (int s = 0; s < 2 * kHalf; ++s) ref.step();
    reference = ref.state_text();
  }
  world_barrier();

  std::vector<std::pair<int, fs::path>> step_n_files;  // (writer ranks, its checkpoint_N), rank 0
  for (std::size_t k = 0; k < cases_for(W).size(); ++k) {
    const Case c = cases_for(W)[k];
    const std::string tag = law + " " + std::to_string(c.writer) + " -> " + std::to_string(c.restart) + " ranks";
    SCOPED_TRACE(tag);
    const std::string prefix =
        "case" + std::to_string(k) + "-w" + std::to_string(c.writer) + "-r" + std::to_string(c.restart);
    const fs::path held_n = tmp.path() / (prefix + "-step_N.h5");
    const fs::path held_cont = tmp.path() / (prefix + "-writer-step_2N.h5");
    const fs::path held_restart = tmp.path() / (prefix + "-restart-step_2N.h5");

    // 1. The writer: 2N steps through run(), a checkpoint every N steps.
    std::string continued;
    {
      SubComm wc(c.writer);
      if (wc.member()) {
        Simulation w(parse_config_text(ini, overrides), wc.comm(), true);
        QuietCout quiet;
        const RunSummary s = w.run();
        EXPECT_EQ(s.steps, 2 * kHalf);
        continued = w.state_text();
      }
    }
    world_barrier();
    if (root) {
      ASSERT_TRUE(fs::is_regular_file(checkpoint_name(kHalf))) << checkpoint_name(kHalf);
      ASSERT_TRUE(fs::is_regular_file(checkpoint_name(2 * kHalf))) << checkpoint_name(2 * kHalf);
      fs::rename(checkpoint_name(kHalf), held_n);
      fs::rename(checkpoint_name(2 * kHalf), held_cont);
      EXPECT_EQ(test::first_difference(reference, continued, "expected", "got"), "")
          << "the writer's run (checkpoints at N and 2N) differs from the uninterrupted 1-rank run";

      // The checkpoint carries contact history: disc pairs and the moving wall's contacts.
      const CheckpointContent cc = inspect(held_n);
      EXPECT_EQ(cc.step, kHalf);
      EXPECT_EQ(cc.complete, 1);
      EXPECT_EQ(cc.ranks, c.writer);
      EXPECT_EQ(cc.slots.size(), 2u);
      EXPECT_GE(cc.pair_rows_with_history, 20u) << "pairs with history at the checkpoint (of " << cc.pair_rows << ")";
      EXPECT_GE(cc.wall_rows_with_history, 3u)
          << "wall rows with history at the checkpoint (of " << cc.wall_rows << ")";
      EXPECT_GE(cc.moving_wall_rows_with_history, 1u) << "no disc touches the moving wall at the checkpoint";
      EXPECT_GT(std::max(std::fabs(cc.moving_wall_x), std::fabs(cc.moving_wall_y)), 1e-4)
          << "the moving wall did not move";
      if (k == 0)
        std::cout << "[ ckpt     ] " << law << ": checkpoint at step " << kHalf << " holds "
                  << cc.pair_rows_with_history << " pair rows and " << cc.wall_rows_with_history
                  << " wall rows with history (" << cc.moving_wall_rows_with_history
                  << " on the moving wall, now at x = " << cc.moving_wall_x << ")\n";
    }
    step_n_files.emplace_back(c.writer, held_n);

    // 2. The restart from checkpoint_N, to run.steps = 2N, through run() (ends with checkpoint_2N).
    std::string restarted;
    RunSummary summary;
    {
      SubComm rc(c.restart);
      if (rc.member()) {
        Simulation r(parse_config_text(ini, overrides), rc.comm(), true, held_n.string());
        EXPECT_EQ(r.step_count(), kHalf);
        QuietCout quiet;
        summary = r.run();
        restarted = r.state_text();
      }
    }
    world_barrier();
    if (root) {
      EXPECT_EQ(summary.steps, kHalf);
      EXPECT_EQ(summary.stop_signal, 0);
      EXPECT_EQ(test::first_difference(reference, restarted, "expected", "got"), "")
          << "N steps + checkpoint + restart + N steps differ from 2N steps";
      EXPECT_EQ(test::first_difference(reference, read_file(out / "final.csv"), "expected", "got"), "")
          << "final.csv of the restart";
      ASSERT_TRUE(fs::is_regular_file(checkpoint_name(2 * kHalf))) << "the restart wrote no checkpoint at its end";
      fs::rename(checkpoint_name(2 * kHalf), held_restart);
      // The whole state at 2N (contact rows and their history included) as the uninterrupted writer's.
      EXPECT_EQ(h5diff(held_cont, held_restart, tmp.path()), "")
          << "checkpoint_2N of the restart differs from the writer's";
    }
    world_barrier();
  }

  if (root) {
    // h5diff sees differences (else the equalities above prove nothing).
    const fs::path n0 = step_n_files.front().second;
    const fs::path cont0 = tmp.path() / ("case0-w" + std::to_string(cases_for(W)[0].writer) + "-r" +
                                         std::to_string(cases_for(W)[0].restart) + "-writer-step_2N.h5");
    EXPECT_NE(h5diff(n0, cont0, tmp.path()), "") << "h5diff finds no difference between steps N and 2N";
    // Checkpoints of step N written on different rank counts are the same file (but for run metadata).
    for (std::size_t k = 1; k < step_n_files.size(); ++k)
      EXPECT_EQ(h5diff(step_n_files.front().second, step_n_files[k].second, tmp.path()), "")
          << "checkpoints of step " << kHalf << " written on " << step_n_files.front().first << " and "
          << step_n_files[k].first << " ranks differ";
  }
}

TEST(Checkpoint, RestartIsBitwiseWithWangRolling) { restart_cases("wang"); }

TEST(Checkpoint, RestartIsBitwiseWithJiangPlasticRolling) { restart_cases("jiang_plastic"); }

// The same with the grid partitioner and a repartition every 500 steps: the decomposition at the checkpoint
// (rebalanced in the writer, fresh in the restart) leaves no trace in the results.
TEST(Checkpoint, RestartIsBitwiseWithRebalancing) {
  restart_cases("wang",
                {"--parallel.partitioner=grid", "--parallel.force_balance=true", "--parallel.balance_every=500"});
}

// A servo wall: its velocity at the first step after the restart comes from the wall load of the step
// before the checkpoint, which the checkpoint carries (/walls/normal_force, /walls/contacts).
TEST(Checkpoint, RestartIsBitwiseWithServoWall) {
  restart_cases("jiang_plastic", {"--walls.control=bottom:servo:2000", "--walls.servo_max_speed=0.2"});
}

// A rough wall that shears: the discs glued to the right wall (their flags) ride up with it at 0.05 m/s
// while the pile is pushed against them; the glue and the wall's motion continue through the restart.
// Two materials (a light and a heavy disc fraction, steel walls) with pair blocks for the linear, coulomb and
// wang laws: the material table and every disc's material travel through the checkpoint.
TEST(Checkpoint, RestartIsBitwiseWithTwoMaterials) {
  restart_cases("wang", {"--material.glass.density=2500", "--material.steel.density=7800",
                         "--scene.materials=glass steel", "--scene.material_fractions=0.6 0.4",
                         "--walls.material=steel", "--linear.glass.steel.zeta=0.3", "--coulomb.steel.steel.mu=0.3",
                         "--wang.glass.wall.steel.mu_r=0.05", "--contact.steel.steel.rolling=false"});
}

// Local damping (run.local_damping): it needs no state, so the restart continues the damped kicks as they were.
TEST(Checkpoint, RestartIsBitwiseWithLocalDamping) { restart_cases("wang", {"--run.local_damping=0.7"}); }

// A rotating wall (docs/physics.md section 8): the moving line replaced by a fixed one (x = 0) and a paddle on
// it, a segment from (0, 0.045) down to its pivot at the origin that turns clockwise at 25 rad/s into the pile. Its
// ends (turned step by step) and its angle travel through the checkpoint.
TEST(Checkpoint, RestartIsBitwiseWithRotatingPaddle) {
  restart_cases("wang", {"--walls.lines=0 0 1 0", "--walls.segments=0 0.045 0 0 -25 0 0"});
}

TEST(Checkpoint, RestartIsBitwiseWithRoughShearingWall) {
  restart_cases("wang", {"--walls.rough=right", "--walls.rough_depth=0.0025", "--walls.control=right:shear:0.05"});
}

// Parallel bonds (docs/bonds.md) between the discs within 0.4 radii of each other at the start, breaking as the
// pile falls and is pushed (before and after the checkpoint): the bonds travel through it (/bonds) to the owners
// of their discs on another rank count, and the checkpoints of step N compare equal whatever the writer's ranks.
TEST(Checkpoint, RestartIsBitwiseWithBreakingBonds) {
  restart_cases("wang", {"--neighbour.skin=0.001", "--bonds.gap=0.4", "--bonds.kb_n=1e9", "--bonds.kb_s=5e8",
                         "--bonds.sigma_c=4e3", "--bonds.tau_c=4e3", "--bonds.sigma_spread=0.5"});
}

}  // namespace
}  // namespace rondel
