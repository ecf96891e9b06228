// Time reversibility of velocity Verlet on a conservative scene. With an undamped linear normal law, no
// friction and no rolling law, every force depends on the positions only, so the scheme is symmetric in time:
// after N steps, negating every velocity and angular velocity and running N more steps retraces the path
// back to the initial positions. The forces stored at the reversal are those of the current positions,
// which is what the first half kick of the return needs (f(x_N) gives v_{N+1/2} = -v_{N-1/2}).
// In exact arithmetic the return is exact; in floating point each drift x + dt v and its reverse round
// differently, and collisions amplify those eps-sized differences, so the test bounds them (see kTol).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

namespace fs = std::filesystem;

// A scratch directory for the scene file, removed when the test ends.
struct ScratchDir : test::TempDir {
  ScratchDir() : test::TempDir("rondel-test-reversibility") {}
};

constexpr int kSide = 6;             // 36 discs on a 6 x 6 grid
constexpr double kSpacing = 0.0101;  // grid spacing [m]: radii below kSpacing/2, so no initial overlap
constexpr double kBox = kSide * kSpacing;

// Writes a polydisperse 6 x 6 grid inside the walled box [0, kBox]^2 with random velocities and spins
// (fixed seed), so that discs collide with each other and with the walls within a few hundred steps.
void write_scene(const fs::path& file) {
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<double> radius(0.0045, 0.0050), speed(-0.3, 0.3), spin(-20.0, 20.0);
  std::ofstream f(file);
  f.precision(17);
  f << "id,x,y,radius,vx,vy,omega\n";
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const double R = radius(rng), vx = speed(rng), vy = speed(rng), w = spin(rng);
      f << j * kSide + i << "," << (i + 0.5) * kSpacing << "," << (j + 0.5) * kSpacing << "," << R << "," << vx << ","
        << vy << "," << w << "\n";
    }
}

struct Snapshot {
  std::vector<Vec2> x, v;
  std::vector<double> w;
};

// Owned discs in ascending gid, so that snapshots compare disc by disc whatever the store's order.
Snapshot snapshot(const DiscStore& D) {
  std::vector<std::size_t> order(D.n_owned());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return D.gid[a] < D.gid[b]; });
  Snapshot s;
  for (std::size_t i : order) {
    s.x.push_back(D.position[i]);
    s.v.push_back(D.velocity[i]);
    s.w.push_back(D.omega[i]);
  }
  return s;
}

struct RoundTrip {
  double max_dx = 0.0;     // largest |x_back - x_0| [m]
  double max_dv = 0.0;     // largest |v_back + v_0| [m/s]
  double max_moved = 0.0;  // largest |x_N - x_0| [m]: how far the discs went before turning back
  std::int64_t contact_steps = 0, wall_contact_steps = 0;
  double KE0 = 0.0, KE_back = 0.0;
};

RoundTrip round_trip(int N, const std::string& law = "--linear.zeta=0") {
  ScratchDir dir;
  const fs::path csv = dir.path() / "grid.csv";
  write_scene(csv);
  const std::string ini = R"(
[domain]
xlo = 0
xhi = 0.0606
ylo = 0
yhi = 0.0606
[contact]
tangential = none
[linear]
k_n = 1e6
[walls]
box = bottom left right top
[scene]
type = csv
)";
  Communicator comm;
  // The checks read every disc from this rank's store: a one-rank run (the binary's normal launch).
  EXPECT_EQ(comm.size(), 1);
  Simulation sim(parse_config_text(ini, {"--scene.file=" + csv.string(), law}), comm, /*write_files=*/false);
  RoundTrip r;
  r.KE0 = sim.kinetic_energy();
  const Snapshot start = snapshot(sim.discs());
  auto count_contacts = [&]() {
    for (double f : sim.pairs().F_n) r.contact_steps += f > 0.0;
    for (double f : sim.wall_rows().F_n) r.wall_contact_steps += f > 0.0;
  };
  for (int s = 0; s < N; ++s) sim.step(), count_contacts();
  const Snapshot turn = snapshot(sim.discs());
  DiscStore& D = sim.discs();
  for (std::size_t i = 0; i < D.n_owned(); ++i) {
    D.velocity[i] = -D.velocity[i];
    D.omega[i] = -D.omega[i];
  }
  for (int s = 0; s < N; ++s) sim.step(), count_contacts();
  const Snapshot back = snapshot(sim.discs());
  r.KE_back = sim.kinetic_energy();
  for (std::size_t i = 0; i < start.x.size(); ++i) {
    const Vec2 dx = back.x[i] - start.x[i], dv = back.v[i] + start.v[i], moved = turn.x[i] - start.x[i];
    r.max_dx = std::max(r.max_dx, std::sqrt(dot(dx, dx)));
    r.max_dv = std::max({r.max_dv, std::sqrt(dot(dv, dv)), 0.005 * std::fabs(back.w[i] + start.w[i])});
    r.max_moved = std::max(r.max_moved, std::sqrt(dot(moved, moved)));
  }
  return r;
}

// N = 200 steps (dt = 0.2 dt_crit, the default): about 16 disc-disc and 6 wall contacts per step, discs moving
// up to 0.7 R. Tolerances: coordinates are ~0.03 m, so one rounding is ~3.5e-18 m; the collisions amplify the
// rounding of the way out and back roughly a hundredfold per 200 steps (observed: 1e-16 m after 2 x 100 steps,
// 3.6e-15 m after 2 x 200, 7.6e-13 m after 2 x 400, and complete loss of the path after 2 x 1600). The bound
// 1e-13 m (2e-11 R, 1.6e-12 of the box) leaves a factor ~30 over the observed 3.6e-15 m; anything that breaks
// the time symmetry of the scheme (a velocity-dependent force, a stale force at the reversal, an asymmetric
// kick) gives errors many orders larger (the weakly damped case below returns 2e-3 m off).
constexpr int kSteps = 200;
constexpr double kTolX = 1e-13;  // [m]
constexpr double kTolV = 3e-11;  // [m/s]; observed 8.9e-13 (speeds ~0.3 m/s, stiff contacts amplify more)

TEST(Reversibility, VelocityVerletRetracesAConservativePacking) {
  const RoundTrip r = round_trip(kSteps);
  std::printf(
      "  %d steps out and back: max |x_back - x0| = %.3e m (moved up to %.3e m), max |v_back + v0| = %.3e m/s, "
      "%lld disc-disc and %lld wall contact-steps, KE change %.2e relative\n",
      kSteps, r.max_dx, r.max_moved, r.max_dv, static_cast<long long>(r.contact_steps),
      static_cast<long long>(r.wall_contact_steps), (r.KE_back - r.KE0) / r.KE0);
  // The scene really collides, and the discs really move, before turning back.
  EXPECT_GT(r.contact_steps, 1000);
  EXPECT_GT(r.wall_contact_steps, 300);
  EXPECT_GT(r.max_moved, 0.002);
  EXPECT_LE(r.max_dx, kTolX);
  EXPECT_LE(r.max_dv, kTolV);
  EXPECT_NEAR(r.KE_back, r.KE0, 1e-12 * r.KE0);
}

TEST(Reversibility, DampingBreaksIt) {
  // The same round trip with a weak normal dashpot (zeta = 0.05) is not reversible: the check above can fail.
  const RoundTrip r = round_trip(kSteps, "--linear.zeta=0.05");
  std::printf("  with zeta = 0.05: max |x_back - x0| = %.3e m, KE back/KE0 = %.4f\n", r.max_dx, r.KE_back / r.KE0);
  EXPECT_GT(r.max_dx, 1e4 * kTolX);
  EXPECT_LT(r.KE_back, 0.99 * r.KE0);
}

}  // namespace
}  // namespace rondel
