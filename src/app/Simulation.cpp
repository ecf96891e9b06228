#include "app/Simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <thread>

#include "app/BondRecords.hpp"
#include "app/OutputNames.hpp"
#include "app/Reports.hpp"
#include "app/Restart.hpp"
#include "app/StartChecks.hpp"
#include "core/Errors.hpp"
#include "core/FaultInjection.hpp"
#include "core/Format.hpp"
#include "core/StopSignal.hpp"
#include "core/WallKinds.hpp"
#include "parallel/Agreement.hpp"
#include "physics/NormalLinear.hpp"
#include "physics/PairConstants.hpp"

namespace rondel {

namespace fs = std::filesystem;

Simulation::Simulation(Config config, const Communicator& comm, bool write_files, const std::string& restart_file)
    : config_(std::move(config)),
      comm_(comm),
      write_files_(write_files),
      neighbours_(0.0),
      files_(config_, comm_, write_files),
      cell_control_(config_),
      reduction_(comm_, config_, Boundaries::controlled(config_.walls) || cell_control_.active()) {
  // Each set-up phase ends in an agreement (parallel/Agreement.hpp): an error that one rank finds (a disc
  // behind a wall in its block of a checkpoint, a file it cannot read) stops every rank, with one message,
  // before the next collective call. The phases that call collectives agree inside.
  agree(comm_, [&] {
    laws_ = law_selection(config_);
    kernel_ = select_kernel(laws_);
    pairs_ = make_contact_table(laws_, false);
    wall_rows_ = make_contact_table(laws_, true);
    if (config_.bonds) bonds_ = ContactTable::bond_table();
    if (config_.bonds && config_.cell_deforms())
      throw InputError(
          "[bonds] in a deforming cell (cell.rate_* or cell.stress_*) is not supported yet: bonds are "
          "computed in a standing box or periodic cell");
    walls_ = config_.walls;
    boundaries_.bind(walls_);
    box0_ = Boundaries::box(walls_, config_.domain);
    resolve_pair_constants(config_.params, config_.materials);
  });
  const bool restart = !restart_file.empty();
  if (restart) {
    load_checkpoint(restart_file);
    keep_rough_walls(restart_file);
  } else {
    config_.run_id = RunFiles::new_run_id(comm_);
    build_discs();
    agree(comm_, [&] {
      resolve_time_step();
      start_checks::check_cell(config_, cell_sizing(), neighbours_.range(R_max_), dt_);
      start_checks::check_initial_motion(config_, discs_);
    });
    distribute_discs();
  }
  setup_boundaries();
  phases_.restart();
  rebuild(!restart);                       // a new scene's discs are on their owners (distribute_discs)
  if (!restart) check_initial_overlaps();  // on the rows just built: every pair within reach
  if (!restart && config_.bonds) create_bonds();
  if (write_files_) {
    stop_if_signalled(restart_file);
    files_.prepare(restart_file, step_);
  }
  if (restart) {
    // Forces, history and ledger come from the file (no recomputation before the first kick); the first
    // step's reduction sums the walls' loads from the rows read, as the interrupted run's step would have.
    if (boundaries_.controlled()) loads_ = Boundaries::local_loads(walls_, discs_, config_.domain, pairs_, wall_rows_);
    if (cell_control_.active()) cell_sums_ = CellControl::local_sums(discs_, config_.domain, pairs_);
    return;
  }
  // Forces at t = 0 for the first half kick: the kernel at the initial state with a zero increment,
  // committing no history and booking no work (KernelOps::initial).
  StepCore::initial_forces(step_inputs(false));
  if (boundaries_.controlled()) {
    boundaries_.measure(walls_, discs_, config_.domain, pairs_, wall_rows_, comm_);
    loads_ = Boundaries::local_loads(walls_, discs_, config_.domain, pairs_, wall_rows_);
  }
  if (cell_control_.active()) cell_sums_ = CellControl::local_sums(discs_, config_.domain, pairs_);
  core_.ledger().start(kinetic_energy());
}

void Simulation::keep_rough_walls(const std::string& path) {
  // The glue travels in the discs' flags: a wall that carries glued discs stays rough whatever the
  // configuration says (a resumed run continues the same boundary).
  const std::vector<std::int64_t> glued = Boundaries::glued_counts(discs_, walls_.size());
  const std::int64_t beyond = comm_.sum(glued.back());
  agree(comm_, [&] {  // every rank sees the same sum: agreed, so that main prints it once
    if (beyond > 0)
      throw InputError("'" + path + "' has discs glued to a wall index beyond its " + std::to_string(walls_.size()) +
                       " walls (/discs/flags)");
  });
  for (std::size_t w = 0; w < walls_.size(); ++w)
    if (comm_.sum(glued[w]) > 0) walls_[w].rough = true;
  boundaries_.bind(walls_);
}

void Simulation::setup_neighbours() {
  // From the radii of every disc (measure_radii). The checks of the discs see this rank's discs only (a
  // block of a checkpoint on --resume): agreed.
  agree(comm_, [&] {
    neighbours_ = NeighbourList(skin_for(R_total_ / static_cast<double>(n_discs_)));
    start_checks::check_cells(config_, neighbours_.range(R_max_));
    check_periodic_lengths();
    for (std::size_t w = 0; w < walls_.size(); ++w)
      for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
        std::string why;
        WallKinds::with(walls_[w].kind,
                        [&]<class K>() { why = K::behind(walls_[w], walls_[w].proximity(discs_.position[i]).dist); });
        if (!why.empty())
          throw InputError("disc " + std::to_string(discs_.gid[i]) + " lies behind wall " + std::to_string(w) + " (" +
                           why + ")");
      }
  });
}

void Simulation::check_periodic_lengths() const {
  const double range = neighbours_.range(R_max_);
  const Domain& d = config_.domain;
  if (d.periodic_x && d.length_x() < 2.0 * range)
    throw ConfigError("domain.xhi - domain.xlo = " + fmt(d.length_x()) + " is below twice the interaction range " +
                      fmt(range) + " (2 x largest radius + neighbour.skin): a periodic length must be at least " +
                      fmt(2 * range));
  if (d.periodic_y && d.length_y() < 2.0 * range)
    throw ConfigError("domain.yhi - domain.ylo = " + fmt(d.length_y()) + " is below twice the interaction range " +
                      fmt(range) + " (2 x largest radius + neighbour.skin): a periodic length must be at least " +
                      fmt(2 * range));
}

Domain Simulation::cell_sizing() const {
  Domain s = config_.domain;
  if (!config_.cell_deforms()) return s;
  // Constant rates: each length changes by the factor (1 + dt L_ii) a step; the smallest is at one end.
  const double n = static_cast<double>(std::max<std::int64_t>(config_.steps, 0));
  const auto smallest = [&](double length, double rate) {
    return std::min(length, length * std::pow(1.0 + dt_ * rate, n));
  };
  s.xhi = s.xlo + smallest(s.length_x(), s.L.xx);
  s.yhi = s.ylo + smallest(s.length_y(), s.L.yy);
  if (s.L.xy != 0.0 || s.tilt != 0.0) s.tilt = 0.5 * s.length_x();
  // A stress-controlled length is unknown beforehand: its grid holds down to half the length now (a smaller
  // cell takes a new grid at the rebuild that finds it, Simulation::follow_cell).
  if (config_.cell_stress_xx > 0.0) s.xhi = s.xlo + 0.5 * s.length_x();
  if (config_.cell_stress_yy > 0.0) s.yhi = s.ylo + 0.5 * s.length_y();
  return s;
}

void Simulation::make_decomposition(bool replicated, double range, const Partition::RectUnits* units) {
  decomposition_ = std::make_unique<Decomposition>(config_.domain, range, config_.partitioner, comm_, cell_sizing());
  weighed_ = units && decomposition_->initial_partition(*units);
  if (!units) decomposition_->initial_partition(discs_, replicated);
  if (decomposition_->empty_ranks() > 0 && comm_.root())
    std::cerr << "rondel: warning: " << decomposition_->empty_ranks() << " of " << comm_.size()
              << " ranks own no cell and will idle; use fewer ranks for this scene\n";
}

void Simulation::setup_boundaries() {
  // The servo's spring and dashpot terms use the stiffest and most damped contact that can load a wall:
  // disc-wall contacts of the heaviest disc and, with rough walls, its contacts with glued discs.
  double m_max = 0.0;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) m_max = std::max(m_max, discs_.mass[i]);
  m_max = comm_.max(m_max);
  // The normal law's own dashpot (NormalLinear::c_n) for an effective mass m.
  auto dashpot = [](const ContactParams& p, double m) {
    ContactBodies b;
    b.m_eff = m;
    return NormalLinear::c_n(p, b);
  };
  // A contact that stiffens with overlap counts with its stiffness and dashpot at the largest overlap allowed, a
  // hysteretic one with its unloading stiffness (stiffest_normal).
  const double u = config_.max_overlap * R_max_;
  auto linear = [&](const ContactParams& p, double m, double R_star) {
    ContactBodies b;
    b.m_eff = m;
    ContactKinematics k;
    k.R_star = R_star, k.u_n = u;
    return stiffest_normal(laws_, ContactInput{p, b, k});
  };
  double k_n = 0.0, c_n = 0.0;
  for (const ContactParams& w : config_.params.walls()) {
    const ContactParams q = linear(w, m_max, R_max_);
    k_n = std::max(k_n, q.k_n), c_n = std::max(c_n, dashpot(q, m_max));
  }
  if (boundaries_.rough())
    for (const ContactParams& p : config_.params.pairs()) {
      const ContactParams q = linear(p, 0.5 * m_max, 0.5 * R_max_);
      k_n = std::max(k_n, q.k_n), c_n = std::max(c_n, dashpot(q, 0.5 * m_max));
    }
  boundaries_ = Boundaries(config_.servo_gain, config_.servo_max_speed, k_n, c_n);
  boundaries_.bind(walls_);
}

void Simulation::resolve_time_step() {
  // Every material's radius range over all ranks, and the materials of the walls.
  std::vector<MaterialInfo> mats;
  for (const Material& m : config_.materials)
    mats.push_back({m.density, m.thickness, INFINITY, 0.0, m.body, m.youngs_modulus, m.poisson_ratio,
                    config_.materials.size() > 1 ? m.name : ""});
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
    MaterialInfo& m = mats[static_cast<std::size_t>(discs_.material[i])];
    m.R_min = std::min(m.R_min, discs_.radius[i]), m.R_max = std::max(m.R_max, discs_.radius[i]);
  }
  for (MaterialInfo& m : mats) m.R_min = -comm_.max(-m.R_min), m.R_max = comm_.max(m.R_max);
  start_checks::check_masses(config_, mats);
  CriticalOptions options{config_.max_overlap, {}};
  for (const Wall& w : walls_)
    if (std::find(options.wall_materials.begin(), options.wall_materials.end(), w.material) ==
        options.wall_materials.end())
      options.wall_materials.push_back(w.material);
  critical_ = critical_time_step(laws_, config_.params, mats, !walls_.empty(), options);
  if (config_.dt == 0.0) {
    dt_ = config_.safety * critical_.dt;
  } else {
    dt_ = config_.dt;
    if (dt_ > critical_.dt && !config_.force_dt)
      throw ConfigError("run.dt = " + fmt(dt_) + " s is above the critical time step " + fmt(critical_.dt) + " s (" +
                        critical_.mode + " mode, " + critical_.pair + "); lower it, leave run.dt = 0 for " +
                        fmt(config_.safety) + " x critical, or set run.force_dt = true");
  }
  double R_min = INFINITY;
  for (const MaterialInfo& m : mats) R_min = std::min(R_min, m.R_min);
  start_checks::check_time_step(config_, critical_, dt_, R_min);
}

void Simulation::resume_time_step(double file_dt, const std::string& path) {
  // A run.dt that differs from the checkpoint's step is the user's new step (resolve_time_step checked it);
  // otherwise the run goes on with the checkpoint's step, which must still be stable with this
  // configuration's contacts and materials (they may have been changed on the command line).
  if (config_.dt != 0.0 && config_.dt != file_dt) return;
  dt_ = file_dt;
  if (dt_ > critical_.dt && !config_.force_dt)
    throw ConfigError("the time step " + fmt(dt_) + " s of the checkpoint '" + path +
                      "' is above the critical time step " + fmt(critical_.dt) + " s of this configuration (" +
                      critical_.mode + " mode, " + critical_.pair +
                      "; a stiffer contact or a lighter material than the run that wrote it?): set run.dt below it, "
                      "or run.force_dt = true");
}

void Simulation::stop_if_signalled(const std::string& restart_file) const {
  // RONDEL_FAULT=setup_pause: set-up waits here (at most a minute) for the signal that a test sends.
  if (injected_fault(FaultSite::setup_pause, comm_.rank())) {
    if (comm_.root()) std::cerr << "rondel: set-up paused (RONDEL_FAULT=setup_pause): waiting for a stop signal\n";
    for (int k = 0; k < 6000 && StopSignal::received() == 0; ++k)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const auto signal = static_cast<int>(comm_.max(static_cast<std::int64_t>(StopSignal::received())));
  agree(comm_, [&] {
    if (signal == 0) return;
    throw StoppedInSetup(std::string("stopped by ") + StopSignal::name(signal) +
                         " during set-up, before anything was written to '" + config_.output + "': " +
                         (restart_file.empty()
                              ? std::string("run the same command again to start the run")
                              : "resume with --resume " + fs::path(restart_file).parent_path().string() +
                                    " (the checkpoint '" + restart_file + "' is as it was)"));
  });
}

void Simulation::load_checkpoint(const std::string& path) {
  // Each read is agreed: a rank's block of the file may be the only one that is short or damaged.
  std::unique_ptr<Restart> file;
  agree(comm_, [&] { file = std::make_unique<Restart>(path, config_, laws_, comm_); });
  const StateHeader& h = file->file_header();
  // The run continues under its id (a file from before the ids starts one).
  config_.run_id = h.run_id.empty() ? RunFiles::new_run_id(comm_) : h.run_id;
  resume_cell(h, path);
  agree(comm_, [&] { file->read_discs(discs_); });
  agree(comm_, [&] { file->read_walls(walls_); });
  box0_.width = h.box_width0;
  box0_.height = h.box_height0;
  measure_radii();
  setup_neighbours();
  agree(comm_, [&] {
    resolve_time_step();
    resume_time_step(h.dt, path);
    start_checks::check_cell(config_, cell_sizing(), neighbours_.range(R_max_), dt_);
  });
  step_ = h.step;
  time_ = h.time;
  route_to_owners();  // the discs read by file block
  agree(comm_, [&] { file->read_rows(pairs_, wall_rows_, discs_, bond_rows()); });
  if (config_.bonds) bond_records::read_breaks(path, breaks_, comm_);
  agree(comm_, [&] { file->read_ledger(core_.ledger()); });
}

void Simulation::resume_cell(const StateHeader& h, const std::string& path) {
  // A cell that has deformed goes on from the file's shape (the configuration's box is where it started) with
  // this configuration's rates (a servo's, the file's); a box that stood still is the configuration's, as before.
  if (!h.has_cell || (h.cell.tilt == 0.0 && !h.cell.L.any())) return;
  Domain& cell = config_.domain;
  agree(comm_, [&] {
    if (!(cell.periodic_x && cell.periodic_y))
      throw ConfigError("'" + path + "' holds a cell that has deformed (tilt " + fmt(h.cell.tilt) +
                        "): resume it with domain.periodic_x = true and domain.periodic_y = true");
  });
  // A stress-controlled component goes on at the rate its servo set last (the servo's state).
  if (config_.cell_stress_xx > 0.0) cell.L.xx = h.cell.L.xx;
  if (config_.cell_stress_yy > 0.0) cell.L.yy = h.cell.L.yy;
  cell.take_shape(h.cell);
  flips_ = h.flips;
}

std::string Simulation::write_checkpoint() {
  settle_errors();
  if (!files_.has_directory())
    throw ConfigError("a checkpoint needs an output directory (this simulation writes no files)");
  // A run with bonds: their rows, and the breaks not yet in a snapshot (the resumed run writes them into its next).
  const RecordTable breaks = bond_records::breaks(breaks_);
  StateExtras extras;
  if (config_.bonds) extras.bonds = &bonds_, extras.breaks = &breaks;
  return files_.write_checkpoint(Restart::header(state(), output::kCheckpoint), discs_, pairs_, wall_rows_, walls_,
                                 extras);
}

void Simulation::write_snapshot() {
  settle_errors();
  const auto n = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
  if (!config_.bonds) {
    files_.write_snapshot(Restart::header(state(), output::kSnapshot), discs_, walls_, n);
    return;
  }
  // The bonds as segments and the breaks since the last snapshot, which are then written.
  const RecordTable segments = bond_records::segments(step_inputs(false).bond_context(), bonds_);
  const RecordTable breaks = bond_records::breaks(breaks_);
  files_.write_snapshot(Restart::header(state(), output::kSnapshot), discs_, walls_, n, {nullptr, &segments, &breaks});
  breaks_.clear();
}

RunState Simulation::state() const {
  return RunState{config_,
                  comm_,
                  laws_,
                  discs_,
                  pairs_,
                  wall_rows_,
                  walls_,
                  core_.ledger(),
                  box0_,
                  step_,
                  time_,
                  dt_,
                  reduction_.imbalance(),
                  exchange_.ghost_count(),
                  migrated_,
                  flips_,
                  regrids_};
}

EnergyLedger Simulation::global_ledger() const { return Reports(state()).global_ledger(); }

double Simulation::kinetic_energy() const { return Reports(state()).kinetic_energy(); }

DiagnosticsRow Simulation::diagnostics() {
  settle_errors();
  summary_ = kernel_.stored(KernelContext{discs_, config_.domain, walls_, config_.params, dt_}, pairs_, wall_rows_);
  if (config_.bonds) {
    summary_.bonds_stored = bonds::stored(step_inputs(false).bond_context(), bonds_);
    summary_.bonds = bonds::booked(discs_, bonds_);
  }
  return Reports(state()).diagnostics(summary_, core_.ledger().scale);
}

MeasuresRow Simulation::measures(const ContactSummary& contacts) {
  boundaries_.measure(walls_, discs_, config_.domain, pairs_, wall_rows_, comm_);
  return Measures(config_.domain, config_.thickness, comm_, flips_)
      .row(step_, time_, discs_, pairs_, wall_rows_, walls_, box0_, contacts);
}

std::string Simulation::state_text() const { return Reports(state()).state_text(); }

void Simulation::write_final(const std::string& path) const { Reports(state()).write_final(path); }

}  // namespace rondel
