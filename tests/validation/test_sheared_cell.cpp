// The deforming periodic cell in whole runs (docs/physics.md section 10, docs/validation.md section 13): a pair of
// touching discs across the sheared boundary gives the forces, couples and history of the same pair inside the
// cell (the same relative position and velocities) to round-off, for every rolling law, through a flip of the
// cell; a lone disc started with the mean flow keeps its velocity and changes it by -gamma_dot L_y at a crossing;
// the kinetic stress ignores a drift of the whole; a stage read from a sheared run starts from its agitation plus
// the new flow; the keys of the cell refuse what they cannot do, naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/Simulation.hpp"
#include "core/Errors.hpp"
#include "physics/LawRegistry.hpp"
#include "support/Format.hpp"
#include "support/Quiet.hpp"
#include "support/TempDir.hpp"

namespace rondel {
namespace {

using test::num;

// One rank (Simulation keeps a reference to its communicator).
const Communicator& self_comm() {
  static const Communicator self(MPI_COMM_SELF);
  return self;
}

constexpr double kR = 0.005;              // the reference disc D5 (docs/developing.md)
constexpr double kLx = 0.04, kLy = 0.05;  // the cell: more than twice the interaction range both ways
constexpr double kRate = 2000.0;          // cell.rate_xy [1/s]: the tilt passes L_x / 2 at step 20
constexpr int kSteps = 400;

// A disc of the scene: its position, velocity and spin.
struct Disc {
  Vec2 x, v;
  double w = 0.0;
};

// The discs (gids 0, 1, ...) in the sheared cell.
std::string cell_ini(const std::string& law, const std::vector<Disc>& discs) {
  std::string csv = "id,x,y,radius,vx,vy,omega\n";
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const Disc& d = discs[i];
    csv += std::to_string(i) + "," + num(d.x.x) + "," + num(d.x.y) + "," + num(kR) + "," + num(d.v.x) + "," +
           num(d.v.y) + "," + num(d.w) + "\n";
  }
  static const test::TempDir dir("rondel-sheared-cell");
  static int files = 0;
  const std::filesystem::path file = dir / ("scene" + std::to_string(files++) + ".csv");
  test::write_file(file, csv);
  return "[run]\nprogress = false\ndt = 1e-5\n[domain]\nxlo = 0\nxhi = " + num(kLx) + "\nylo = 0\nyhi = " + num(kLy) +
         "\nperiodic_x = true\nperiodic_y = true\n[cell]\nrate_xy = " + num(kRate) +
         "\nflow_start = false\n[material]\ndensity = 2650\n[linear]\nk_n = 1e6\nzeta = 0.2\n[coulomb]\n"
         "k_s = 7.5e5\nmu = 0.5\n[contact]\nrolling = " +
         law + "\n[scene]\ntype = csv\nfile = " + file.string() + "\nmax_initial_overlap = 0.2\n";
}

std::vector<std::string> example_options(const std::string& law) {
  const LawInfo* info = law_catalog().rolling.find(law);
  return info && info->block ? info->block->example_options() : std::vector<std::string>{};
}

// The row of the pair (zeros while it has none: an open contact keeps no history) and both discs' forces and
// torques, in gid order.
std::vector<double> snapshot(const Simulation& s) {
  const ContactTable& t = s.pairs();
  const std::size_t columns = 2 + static_cast<std::size_t>(t.couples()) + t.slot.size();
  std::vector<double> out(columns, 0.0);
  for (std::size_t r = 0; r < t.size(); ++r) {
    if (t.i1[r] >= static_cast<std::int32_t>(s.discs().n_owned())) continue;
    std::size_t k = 0;
    out[k++] = t.F_n[r], out[k++] = t.F_t[r];
    if (t.couples() > 0) out[k++] = t.M1[r];
    if (t.couples() > 1) out[k++] = t.M2[r];
    for (const auto& slot : t.slot) out[k++] = slot[r];
  }
  const DiscStore& d = s.discs();
  for (std::int64_t gid : {0, 1})
    for (std::size_t i = 0; i < d.n_owned(); ++i)
      if (d.gid[i] == gid) out.insert(out.end(), {d.force[i].x, d.force[i].y, d.torque[i]});
  return out;
}

TEST(ShearedCell, APairAcrossTheBoundaryIsThePairInsideForEveryRollingLaw) {
  const Domain cell = [] {
    Domain d;
    d.xhi = kLx, d.yhi = kLy, d.periodic_x = d.periodic_y = true, d.L.xy = kRate;
    d.rates();
    return d;
  }();
  // Disc 1 and disc 2 at 1.9 R apart, 30 degrees off the vertical, approaching and spinning.
  const Vec2 d12{0.95 * kR, 1.9 * kR * std::cos(std::asin(0.5))};
  const Vec2 v1{0.01, -0.02}, v2{-0.03, 0.01};
  const double w1 = 10.0, w2 = -5.0;
  // Inside: in the middle. Across: disc 1 just below the top, disc 2's image above it, so disc 2 itself is at the
  // bottom, one lattice vector b = (tilt 0, L_y) lower, moving slower by db/dt = (gamma_dot L_y, 0).
  const Vec2 in1{0.02, 0.02}, in2 = in1 + d12;
  const Vec2 across1{0.02, kLy - 0.4 * kR}, across2 = across1 + d12 - Vec2{0.0, kLy};
  const Vec2 across_v2 = v2 - cell.vb;
  int laws = 0;
  for (const LawInfo& law : law_catalog().rolling.laws) {
    SCOPED_TRACE(law.keyword);
    const std::vector<std::string> o = example_options(law.keyword);
    Simulation inside(parse_config_text(cell_ini(law.keyword, {{in1, v1, w1}, {in2, v2, w2}}), o), self_comm(), false);
    Simulation across(parse_config_text(cell_ini(law.keyword, {{across1, v1, w1}, {across2, across_v2, w2}}), o),
                      self_comm(), false);
    std::vector<std::vector<double>> a, b;
    int first_flip = -1;
    for (int s = 0; s < kSteps; ++s) {
      inside.step(), across.step();
      a.push_back(snapshot(inside)), b.push_back(snapshot(across));
      if (first_flip < 0 && across.state().flips != 0) first_flip = s;
    }
    ASSERT_GE(first_flip, 0) << "the cell did not flip within the run";
    EXPECT_GT(a[static_cast<std::size_t>(first_flip)][0], 0.0) << "the discs were apart at the flip";
    // Each value against the largest of its kind over the run.
    const std::size_t n = a.front().size();
    std::vector<double> scale(n, 0.0);
    for (const auto& row : a)
      for (std::size_t k = 0; k < n; ++k) scale[k] = std::max(scale[k], std::fabs(row[k]));
    std::size_t contact_steps = 0;
    for (int s = 0; s < kSteps; ++s) {
      ASSERT_EQ(b[s].size(), n);
      if (a[s][0] > 0.0) ++contact_steps;
      for (std::size_t k = 0; k < n; ++k)
        ASSERT_NEAR(a[s][k], b[s][k], 1e-12 * scale[k] + 1e-300) << "step " << s + 1 << ", value " << k;
    }
    EXPECT_GT(contact_steps, 30u) << "the discs were hardly in contact";
    ++laws;
  }
  EXPECT_GE(laws, 9);
}

// A lone disc started with the mean flow's velocity keeps it (no force acts); each crossing of the sheared
// boundary changes it by -gamma_dot L_y (upwards) and nothing else.
TEST(ShearedCell, ALoneDiscKeepsItsVelocityAndChangesItAtACrossing) {
  const Vec2 x0{0.01, kLy - 0.002};
  Simulation s(parse_config_text(cell_ini("none", {{x0, {0.0, 0.5}}}), {"--cell.flow_start=true"}), self_comm(), false);
  const auto disc0 = [] { return std::size_t{0}; };
  const Vec2 v0 = s.discs().velocity[disc0()];
  EXPECT_EQ(v0.x, kRate * x0.y);  // the flow's velocity at its height, added
  for (int k = 0; k < 1000; ++k) s.step();
  const Vec2 v = s.discs().velocity[disc0()];
  const double y = s.discs().position[disc0()].y;
  ASSERT_LT(y, 0.5 * kLy) << "the disc did not cross the top";
  EXPECT_NEAR(v.x, v0.x - kRate * kLy, 1e-12 * kRate * kLy);
  EXPECT_EQ(v.y, v0.y);
}

// The kinetic stress is the agitation apart from the mean flow and from the discs' mean velocity: two equal discs
// far apart moving at U + w and U - w over the flow have K_xx = 2 m w^2 / (A t), whatever the drift U.
TEST(ShearedCell, TheKineticStressIsTheAgitationApartFromAnyDrift) {
  constexpr double kW = 0.3;
  for (const double drift : {0.0, 7.0}) {
    const std::vector<Disc> discs{{{0.01, 0.01}, {drift + kW, 0.0}}, {{0.03, 0.035}, {drift - kW, 0.0}}};
    Simulation s(parse_config_text(cell_ini("none", discs), {"--cell.flow_start=true"}), self_comm(), false);
    const MeasuresRow m = s.measures();
    const double mass = s.discs().mass[0], area = kLx * kLy;  // thickness 1 m
    EXPECT_NEAR(m.kxx, 2.0 * mass * kW * kW / area, 1e-12 * mass * kW * kW / area) << "drift " << drift;
    EXPECT_NEAR(m.kyy, 0.0, 1e-12 * mass * kW * kW / area) << "drift " << drift;
    EXPECT_NEAR(m.kxy, 0.0, 1e-12 * mass * kW * kW / area) << "drift " << drift;
  }
}

// A new stage read from a sheared run's checkpoint (scene.type = file) starts each disc with its velocity apart
// from the file's flow (rate r1) plus the new run's (rate r2): v = v_file + (r2 - r1) (y - ylo), so that a stage
// at another rate meets no jump of the flow at the boundary.
TEST(ShearedCell, AFileStageStartsFromItsAgitationPlusTheNewFlow) {
  const test::TempDir dir("rondel-sheared-stage");
  const std::string first = (dir / "first").string();
  const std::vector<Disc> discs{{{0.01, 0.01}, {0.2, 0.1}, 3.0}, {{0.03, 0.035}, {-0.1, 0.05}, -1.0}};
  Simulation a(parse_config_text(cell_ini("none", discs), {"--cell.flow_start=true", "--run.steps=30",
                                                           "--run.output=" + first, "--output.checkpoint_at_end=true"}),
               self_comm(), true);
  {
    test::QuietCout quiet;
    a.run();
  }
  constexpr double kRate2 = 500.0;
  Simulation b(parse_config_text(cell_ini("none", discs), {"--scene.type=file", "--scene.file=" + first,
                                                           "--cell.rate_xy=" + num(kRate2), "--cell.flow_start=true"}),
               self_comm(), false);
  ASSERT_EQ(b.discs().n_owned(), a.discs().n_owned());
  const double ylo = a.config().domain.ylo;
  for (std::size_t i = 0; i < a.discs().n_owned(); ++i) {
    std::size_t j = 0;
    while (b.discs().gid[j] != a.discs().gid[i]) ++j;
    const Vec2 va = a.discs().velocity[i], vb = b.discs().velocity[j], x = a.discs().position[i];
    EXPECT_EQ(b.discs().position[j].x, x.x);
    EXPECT_NEAR(vb.x, va.x + (kRate2 - kRate) * (x.y - ylo), 1e-12 * kRate * kLy) << "disc " << a.discs().gid[i];
    EXPECT_EQ(vb.y, va.y);
    EXPECT_EQ(b.discs().omega[j], a.discs().omega[i]);
  }
}

// A random gas of 250 discs in a periodic cell, both lengths servo-controlled to a contact stress of 1e5 Pa
// (cell.stress_xx, stress_yy): compressed until it jams, then held. Then sheared at constant S_yy. The ledger,
// with the cell's work W_cell (the pairs across the moving boundary and the wraps that shift velocities),
// balances to the integration error; without W_cell the residual would be of the order of the kinetic energy.
std::string gas_ini() {
  return "[run]\nprogress = false\n[domain]\nxlo = 0\nxhi = 0.045\nylo = 0\nyhi = 0.045\nperiodic_x = true\n"
         "periodic_y = true\n[cell]\nstress_xx = 1e5\nstress_yy = 1e5\nservo_gain = 4\nservo_max_rate = 4\n"
         "[material]\ndensity = 2650\n[linear]\nk_n = 1e8\ne = 0.3\n[coulomb]\nk_s = 7.5e7\nmu = 0.1\n[scene]\n"
         "type = random\ncount = 250\nradius_min = 0.0008\nradius_max = 0.0012\nseed = 3\n";
}

TEST(ShearedCell, AServoHoldsTheCellsStressAndTheLedgerBalances) {
  Simulation s(parse_config_text(gas_ini(), {}), self_comm(), false);
  double worst = 0.0;
  for (int k = 0; k < 130; ++k) {
    s.advance(1000, [] { return std::int64_t{0}; });
    worst = std::max(worst, s.diagnostics().residual);
  }
  const MeasuresRow m = s.measures();
  EXPECT_NEAR(m.sxx, 1e5, 1e3);
  EXPECT_NEAR(m.syy, 1e5, 1e3);
  EXPECT_GT(m.phi, 0.8);
  EXPECT_LT(m.cell_lx, 0.035);
  EXPECT_LT(worst, 1e-3) << "the ledger's largest relative residual while the cell shrank";
  const EnergyLedger ledger = s.global_ledger();
  EXPECT_GT(ledger.W_cell, 10.0 * worst * ledger.scale) << "the cell's work is what the balance rests on";
}

TEST(ShearedCell, BadCellKeysAreRefusedNamingTheKey) {
  const std::string base = cell_ini("none", {{{0.01, 0.01}, {}}, {{0.03, 0.03}, {}}});
  const auto refused = [&](const std::vector<std::string>& o) {
    try {
      Simulation s(parse_config_text(base, o), self_comm(), false);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refused({"--domain.periodic_y=false"}).find("cell.rate_xy"), std::string::npos);
  EXPECT_NE(refused({"--walls.lines=0 0 1 0"}).find("walls.lines"), std::string::npos);
  EXPECT_NE(refused({"--cell.rate_xy=1e9"}).find("cell.rate_xy"), std::string::npos);
  EXPECT_NE(refused({"--cell.rate_xx=-1e5"}).find("cell.rate_xx"), std::string::npos);
  // A cell that would shrink below twice the interaction range over the run.
  EXPECT_NE(refused({"--cell.rate_yy=-300", "--run.steps=100000"}).find("cell.rate_yy"), std::string::npos);
  EXPECT_NE(refused({"--cell.rate_xy=nan"}).find("cell.rate_xy"), std::string::npos);
  EXPECT_NE(refused({"--cell.stress_yy=1e5"}).find("cell.servo_gain"), std::string::npos);  // a target, no gain
  EXPECT_NE(refused({"--cell.stress_xx=1e5", "--cell.servo_gain=1", "--cell.rate_xx=1"}).find("cell.stress_xx"),
            std::string::npos);
  EXPECT_NE(refused({"--cell.stress_xx=-1"}).find("cell.stress_xx"), std::string::npos);
  EXPECT_EQ(refused({}), "");
}

}  // namespace
}  // namespace rondel
