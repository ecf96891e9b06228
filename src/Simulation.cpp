#include "Simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "core/Errors.hpp"
#include "core/Integrator.hpp"
#include "core/ExactSum.hpp"
#include "core/SceneBuilder.hpp"
#include "core/StopSignal.hpp"
#include "physics/Restitution.hpp"

namespace rondel {

namespace fs = std::filesystem;

namespace {
double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
std::string fmt(double v, int precision = 6) {
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}
}  // namespace

Simulation::Simulation(Config config, const Communicator& comm, bool write_files, const std::string& restart_file)
    : config_(std::move(config)), comm_(comm), write_files_(write_files), neighbours_(0.0) {
  laws_ = law_selection(config_);
  kernel_ = select_kernel(laws_);
  pairs_ = make_contact_table(laws_);
  wall_rows_ = make_contact_table(laws_);
  walls_ = config_.walls;
  controlled_walls_ = Boundaries::controlled(walls_);
  rough_walls_ = Boundaries::any_rough(walls_);
  box0_ = Boundaries::box(walls_, config_.domain);
  for (ContactParams* p : {&config_.params.pair(0, 0), &config_.params.wall(0)})
    if (p->e_n > 0.0) p->zeta_n = zeta_from_restitution(p->e_n);
  const bool restart = !restart_file.empty();
  if (restart) {
    load_checkpoint(restart_file);
    // The glue travels in the discs' flags: a wall that carries glued discs stays rough whatever the
    // configuration says (a resumed run continues the same boundary).
    const std::vector<std::int64_t> glued = Boundaries::glued_counts(discs_, walls_.size());
    if (comm_.sum(glued.back()) > 0)
      throw InputError("'" + restart_file + "' has discs glued to a wall index beyond its " +
                       std::to_string(walls_.size()) + " walls (/discs/flags)");
    for (std::size_t w = 0; w < walls_.size(); ++w)
      if (comm_.sum(glued[w]) > 0) walls_[w].rough = true;
    rough_walls_ = Boundaries::any_rough(walls_);
  } else {
    build_discs();
    resolve_time_step();
    check_initial_state();
    distribute_discs();
  }
  setup_boundaries();
  if (write_files_) prepare_output(restart);
  rebuild();
  if (restart) return;  // forces, history and ledger come from the file (no recomputation before the first kick)
  // Forces at t = 0 for the first half kick: the kernel at the initial state with a zero increment,
  // committing no history and booking no work (KernelOps::initial).
  kernel_.initial(KernelContext{discs_, config_.domain, walls_, config_.params, 0.0}, pairs_, wall_rows_);
  assembly_.assemble(discs_, config_.gravity, pairs_, wall_rows_);
  if (controlled_walls_) boundaries_.measure(walls_, discs_, pairs_, wall_rows_, comm_);
  ledger_.start(kinetic_energy());
}

void Simulation::build_discs() {
  const std::string dir = config_.source_file.empty() ? "" : fs::path(config_.source_file).parent_path().string();
  const auto scene = config_.scene.type == "file" ? scene_from_file() : build_scene(config_.scene, config_.domain, dir);
  if (scene.empty())
    throw InputError(config_.scene.type == "csv"
                         ? "scene.file '" + config_.scene.file + "' holds no discs: the scene is empty"
                         : "the scene has no discs (scene.type = " + config_.scene.type + ")");
  discs_.reserve(scene.size());
  for (const auto& d : scene) {
    Vec2 x = d.x;
    config_.domain.wrap(x);
    if (!config_.domain.contains(x))
      throw InputError("disc " + std::to_string(d.gid) + " at (" + fmt(d.x.x) + ", " + fmt(d.x.y) +
                       ") lies outside the domain [" + fmt(config_.domain.xlo) + ", " + fmt(config_.domain.xhi) +
                       "] x [" + fmt(config_.domain.ylo) + ", " + fmt(config_.domain.yhi) + "]");
    discs_.add(d.gid, 0, d.radius, config_.density, config_.thickness, x, d.v, d.omega);
  }
  if (rough_walls_) {  // every rank holds the whole scene here
    double R_max = 0.0;
    for (std::size_t i = 0; i < discs_.n_owned(); ++i) R_max = std::max(R_max, discs_.radius[i]);
    Boundaries::glue(discs_, walls_, config_.rough_depth > 0.0 ? config_.rough_depth : 2.0 * comm_.max(R_max));
  }
  setup_neighbours();
}

void Simulation::setup_neighbours() {
  // From the radii of every disc (the discs may be spread over ranks already, on a restart).
  double R_max = 0.0;
  ExactSum R_sum;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) R_max = std::max(R_max, discs_.radius[i]), R_sum += discs_.radius[i];
  R_max = comm_.max(R_max);
  const auto n = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
  const double skin = config_.skin > 0.0 ? config_.skin : 0.25 * comm_.exact_sum(R_sum) / static_cast<double>(n);
  neighbours_ = NeighbourList(skin);
  const double range = neighbours_.range(R_max);
  const Domain& d = config_.domain;
  if (d.periodic_x && d.length_x() < 2.0 * range)
    throw ConfigError("domain.xhi - domain.xlo = " + fmt(d.length_x()) + " is below twice the interaction range " +
                      fmt(range) + " (2 x largest radius + skin): a periodic length must be at least " + fmt(2 * range));
  if (d.periodic_y && d.length_y() < 2.0 * range)
    throw ConfigError("domain.yhi - domain.ylo = " + fmt(d.length_y()) + " is below twice the interaction range " +
                      fmt(range) + " (2 x largest radius + skin): a periodic length must be at least " + fmt(2 * range));
  for (std::size_t w = 0; w < walls_.size(); ++w)
    for (std::size_t i = 0; i < discs_.n_owned(); ++i)
      if (walls_[w].kind == Wall::Kind::line && walls_[w].proximity(discs_.position[i]).dist < 0.0)
        throw InputError("disc " + std::to_string(discs_.gid[i]) + " lies behind wall " + std::to_string(w) +
                         " (its centre is on the far side of the line)");
}

void Simulation::distribute_discs() {
  // Every rank built the whole scene; each keeps the discs of its cells.
  make_decomposition(true);
  std::vector<bool> elsewhere(discs_.n_owned());
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) elsewhere[i] = decomposition_->owner(discs_.position[i]) != comm_.rank();
  discs_.remove_owned(elsewhere);
}

void Simulation::make_decomposition(bool replicated) {
  double R_max = 0.0;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) R_max = std::max(R_max, discs_.radius[i]);
  R_max = comm_.max(R_max);
  const auto partitioner = config_.partitioner == "grid" ? Decomposition::Partitioner::grid
                                                          : Decomposition::Partitioner::metis;
  decomposition_ = std::make_unique<Decomposition>(config_.domain, neighbours_.range(R_max), partitioner, comm_);
  std::vector<long> weights(decomposition_->grid().size(), 1);  // as Decomposition::cell_work, discs only
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) weights[decomposition_->grid().cell_of(discs_.position[i])] += 100;
  if (!replicated) weights = decomposition_->sum_over_ranks(weights);
  decomposition_->initial_partition(weights);
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
  auto dashpot = [](const ContactParams& p, double m) {
    return p.c_n_fixed >= 0.0 ? p.c_n_fixed : 2.0 * p.zeta_n * std::sqrt(m * p.k_n);
  };
  const ContactParams& w = config_.params.wall(0);
  double k_n = w.k_n, c_n = dashpot(w, m_max);
  if (rough_walls_) {
    const ContactParams& p = config_.params.pair(0, 0);
    k_n = std::max(k_n, p.k_n);
    c_n = std::max(c_n, dashpot(p, 0.5 * m_max));
  }
  boundaries_ = Boundaries(config_.servo_gain, config_.servo_max_speed, k_n, c_n);
}

void Simulation::resolve_time_step() {
  double R_min = INFINITY, R_max = 0.0;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i)
    R_min = std::min(R_min, discs_.radius[i]), R_max = std::max(R_max, discs_.radius[i]);
  R_min = -comm_.max(-R_min);
  R_max = comm_.max(R_max);
  const std::vector<MaterialInfo> mats{{config_.density, config_.thickness, R_min, R_max}};
  critical_ = critical_time_step(laws_, config_.params, mats, !walls_.empty());
  if (config_.dt == 0.0) {
    dt_ = config_.safety * critical_.dt;
  } else {
    dt_ = config_.dt;
    if (dt_ > critical_.dt && !config_.force_dt)
      throw ConfigError("run.dt = " + fmt(dt_) + " s is above the critical time step " + fmt(critical_.dt) +
                        " s (" + critical_.mode + " mode, " + critical_.pair +
                        "); lower it, leave run.dt = 0 for " + fmt(config_.safety) +
                        " x critical, or set run.force_dt = true");
  }
}

void Simulation::check_initial_state() {
  ContactTable pairs = make_contact_table(laws_), walls = make_contact_table(laws_);
  NeighbourList probe(neighbours_.skin());
  probe.build(discs_, config_.domain, walls_, config_.params, pairs, pairs, walls, walls);
  std::int64_t count = 0;
  double worst = 0.0;
  std::string where;
  auto consider = [&](double u_n, double R, const std::string& what) {
    const double ratio = u_n / R;
    if (ratio <= config_.scene.max_initial_overlap) return;
    ++count;
    if (ratio > worst) worst = ratio, where = what;
  };
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    const auto i = static_cast<std::size_t>(pairs.i1[r]), j = static_cast<std::size_t>(pairs.i2[r]);
    const Vec2 d = config_.domain.separation(discs_.position[i], discs_.position[j]);
    consider(discs_.radius[i] + discs_.radius[j] - std::sqrt(dot(d, d)), std::min(discs_.radius[i], discs_.radius[j]),
             "discs " + std::to_string(discs_.gid[i]) + " and " + std::to_string(discs_.gid[j]));
  }
  for (std::size_t r = 0; r < walls.size(); ++r) {
    const auto i = static_cast<std::size_t>(walls.i1[r]);
    consider(discs_.radius[i] - walls_[walls.i2[r]].proximity(discs_.position[i]).dist, discs_.radius[i],
             "disc " + std::to_string(discs_.gid[i]) + " and wall " + std::to_string(walls.i2[r]));
  }
  if (count > 0)
    throw InputError(std::to_string(count) + " initial overlaps exceed scene.max_initial_overlap = " +
                     fmt(config_.scene.max_initial_overlap) + " of the smaller radius; the worst is " + fmt(worst) +
                     " between " + where);
}


void Simulation::log(const std::string& line) {
  if (!comm_.root()) return;
  if (write_files_) std::cout << line << '\n';
  if (log_.is_open()) log_ << line << '\n' << std::flush;
}

void Simulation::rebuild() {
  // Discs go to their cell owners with their contact rows; the rows (local and received) then serve as
  // the history source of the new neighbour list.
  const auto t0 = std::chrono::steady_clock::now();
  const DiscExchange::Counts moved = exchange_.migrate(discs_, pairs_, wall_rows_, *decomposition_, comm_);
  migrated_ += moved.sent;
  exchange_.build_ghosts(discs_, *decomposition_, comm_);
  comm_seconds_ += seconds_since(t0);
  const ContactTable old_pairs = pairs_, old_walls = wall_rows_;
  neighbours_.build(discs_, config_.domain, walls_, config_.params, old_pairs, pairs_, old_walls, wall_rows_);
  assembly_.build(discs_, pairs_, wall_rows_);
  rebalance_due_ = false;
}

void Simulation::balance_load() {
  // Work: owned discs and booked rows (Decomposition::cell_work counts the same).
  std::size_t booked = 0;
  for (std::size_t r = 0; r < pairs_.size(); ++r) booked += static_cast<std::size_t>(pairs_.i1[r]) < discs_.n_owned();
  const double work = static_cast<double>(discs_.n_owned() + booked);
  const double max = comm_.max(work), mean = comm_.sum(work) / comm_.size();
  imbalance_ = mean > 0.0 ? max / mean : 1.0;
  if (comm_.size() == 1 || (!config_.force_balance && imbalance_ <= config_.balance_threshold)) return;
  if (decomposition_->repartition(decomposition_->cell_work(discs_, pairs_))) rebalance_due_ = true;
}

void Simulation::step() {
  // 1. Half kick and drift of owned discs (wrapping into the periodic box).
  const double W_g = Integrator::half_kick_drift(discs_, config_.domain, dt_, config_.gravity);
  // 2. Move walls: servo and strain-rate walls steer from the last step's exact wall loads.
  if (controlled_walls_) boundaries_.steer(walls_, config_.domain, config_.thickness, dt_);
  for (auto& w : walls_) w.move(dt_);
  if (rough_walls_) Boundaries::move_glued(discs_, walls_, config_.domain, dt_);
  // 3. Rebuild the neighbour list when a disc (global max) has moved more than half the skin.
  const double moved = neighbours_.max_displacement(discs_, config_.domain);
  const auto t0 = std::chrono::steady_clock::now();
  const double disp = comm_.max(moved);
  comm_seconds_ += seconds_since(t0);
  if (rebalance_due_ || neighbours_.needs_rebuild(disp, walls_)) {
    rebuild();
  } else {
    const auto t1 = std::chrono::steady_clock::now();
    exchange_.update_ghosts(discs_, comm_);
    comm_seconds_ += seconds_since(t1);
  }
  // 4-6. Contact kernel over every row, then per-disc sums in ascending partner gid (gravity first).
  LedgerStep work;
  kernel_.run(KernelContext{discs_, config_.domain, walls_, config_.params, dt_, config_.max_overlap}, pairs_,
              wall_rows_, work);
  const auto t2 = std::chrono::steady_clock::now();
  if (comm_.any(work.worst_overlap > 0.0)) report_overlap(work);
  comm_seconds_ += seconds_since(t2);
  if (rough_walls_) work.W_w += Boundaries::glued_work_half(discs_, dt_);  // the last step's reaction forces
  assembly_.assemble(discs_, config_.gravity, pairs_, wall_rows_);
  if (rough_walls_) work.W_w += Boundaries::glued_work_half(discs_, dt_);  // this step's
  if (controlled_walls_) boundaries_.measure(walls_, discs_, pairs_, wall_rows_, comm_);
  // 7. Second half kick.
  Integrator::half_kick(discs_, dt_);
  ledger_.add(work, W_g);
  ++step_;
  time_ += dt_;
  if (config_.balance_every > 0 && step_ % config_.balance_every == 0) balance_load();
}

void Simulation::report_overlap(const LedgerStep& work) const {
  std::string where;
  if (work.worst_overlap > 0.0) {
    where = work.worst_at_wall ? "disc " + std::to_string(work.worst_key.lo) + " and wall " + std::to_string(work.worst_key.hi)
                               : "discs " + std::to_string(work.worst_key.lo) + " and " + std::to_string(work.worst_key.hi);
    where += std::isinf(work.worst_overlap) ? " have coincident centres"
                                            : " overlap by " + fmt(work.worst_overlap) + " of the smaller radius";
  } else {
    where = "another rank found an overlap";
  }
  throw InstabilityError("step " + std::to_string(step_ + 1) + " (t = " + fmt(time_ + dt_) + " s): " + where +
                         ", above run.max_overlap = " + fmt(config_.max_overlap) +
                         ". The linear contact is not valid there: stiffen the contacts (linear.k_n), slow the "
                         "impact, or lower run.dt if the run became unstable");
}

std::string Simulation::most_energetic_disc() const {
  double best = -1.0;
  std::int64_t gid = -1;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
    const double ke = 0.5 * discs_.mass[i] * dot(discs_.velocity[i], discs_.velocity[i]) +
                      0.5 * discs_.inertia[i] * discs_.omega[i] * discs_.omega[i];
    if (ke > best || std::isnan(ke)) best = std::isnan(ke) ? INFINITY : ke, gid = discs_.gid[i];
  }
  const double top = comm_.max(best);
  const std::int64_t who = comm_.max(best == top ? gid : std::int64_t{-1});
  return std::to_string(who) + " (kinetic energy " + fmt(top) + " J)";
}

void Simulation::check_stability(const DiagnosticsRow& row) const {
  if (!std::isfinite(row.ke_trans + row.ke_rot))
    throw InstabilityError("step " + std::to_string(row.step) + ": the kinetic energy is not finite");
  if (row.residual > config_.max_residual)
    throw InstabilityError("step " + std::to_string(row.step) + ": the energy ledger residual reached " +
                           fmt(row.residual) + " of the energy scale (run.max_residual = " + fmt(config_.max_residual) +
                           "): energy grows with no work done, the integration is unstable; the most energetic disc is " +
                           most_energetic_disc() + "; lower run.dt or run.safety");
}

std::string Simulation::state_text() const {
  struct Record {
    std::int64_t gid;
    double x, y, vx, vy, theta, omega;
  };
  ByteBuffer mine;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i)
    mine.put(Record{discs_.gid[i], discs_.position[i].x, discs_.position[i].y, discs_.velocity[i].x,
                    discs_.velocity[i].y, discs_.theta[i], discs_.omega[i]});
  const auto all = comm_.gather(mine);
  if (!comm_.root()) return "";
  std::vector<Record> records;
  for (const ByteBuffer& b : all) {
    ByteReader r(b.bytes.data(), b.bytes.size());
    while (!r.done()) records.push_back(r.get<Record>());
  }
  std::sort(records.begin(), records.end(), [](const Record& a, const Record& b) { return a.gid < b.gid; });
  std::string out = "gid,x,y,vx,vy,theta,omega\n";
  char buf[512];
  for (const Record& d : records) {
    std::snprintf(buf, sizeof buf, "%lld,%a,%a,%a,%a,%a,%a\n", static_cast<long long>(d.gid), d.x, d.y, d.vx, d.vy,
                  d.theta, d.omega);
    out += buf;
  }
  return out;
}

RunSummary Simulation::run() {
  const auto n_discs = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
  log("Rondel: " + std::to_string(n_discs) + " discs, " + std::to_string(walls_.size()) + " walls, " +
      std::to_string(comm_.size()) + " rank(s); laws: normal " + config_.normal_law + ", tangential " +
      config_.tangential_law + ", rolling " + config_.rolling_law);
  if (rough_walls_) {
    const std::vector<std::int64_t> glued = Boundaries::glued_counts(discs_, walls_.size());
    std::string line = "rough walls:";
    for (std::size_t w = 0; w < walls_.size(); ++w) {
      if (!walls_[w].rough) continue;
      const std::int64_t n = comm_.sum(glued[w]);
      line += " wall " + std::to_string(w) + " carries " + std::to_string(n) + " glued discs" +
              (n == 0 ? " (warning: none; glue happens at the start of a stage, within walls.rough_depth of the wall)" : "") + ";";
    }
    log(line.substr(0, line.size() - 1));
  }
  log("time step " + fmt(dt_) + " s = " + fmt(dt_ / critical_.dt, 4) + " x critical " + fmt(critical_.dt) +
      " s, limited by the " + critical_.mode + " mode (" + critical_.pair + ")");
  log("neighbour skin " + fmt(neighbours_.skin()) + " m; output in " + (write_files_ ? config_.output : "(none)") +
      (step_ > 0 ? "; resumed at step " + std::to_string(step_) : ""));
  log("resolved configuration:\n" + config_.resolved_text);
  const std::int64_t first = step_, remaining = std::max<std::int64_t>(0, config_.steps - step_);
  ProgressLine progress(remaining, n_discs, write_files_ && config_.progress && comm_.root());
  StopSignal::install();
  RunSummary sum;
  const auto start = std::chrono::steady_clock::now();
  auto last_checkpoint = start;
  std::int64_t checkpointed = -1;
  auto record = [&]() {
    const DiagnosticsRow row = diagnostics();
    if (comm_.root()) diag_.write(row);
    check_stability(row);
    if (!write_files_) return;
    const MeasuresRow m = measures(summary_);
    if (comm_.root()) measures_ << m.csv() << '\n';
  };
  auto checkpoint = [&]() {
    wall_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count();
    last_checkpoint = std::chrono::steady_clock::now();
    sum.last_checkpoint = write_checkpoint();
    checkpointed = step_;
  };
  try {
    if (step_ == 0) record();
    while (step_ < config_.steps) {
      step();
      if (step_ % config_.diag_every == 0 || step_ == config_.steps) record();
      if (files_ && config_.snapshot_every > 0 && step_ % config_.snapshot_every == 0) write_snapshot();
      // Every rank agrees on the step of a signal or of a wall-clock checkpoint (rank 0's clock decides).
      const double minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count() / 60.0;
      const bool timed = comm_.root() && config_.checkpoint_minutes > 0.0 && minutes >= config_.checkpoint_minutes;
      // One reduction for both: the signal number times 2, plus 1 for a due wall-clock checkpoint.
      const std::int64_t flags = comm_.max(2 * static_cast<std::int64_t>(StopSignal::received()) + (timed ? 1 : 0));
      const std::int64_t signal = flags / 2;
      const bool timed_any = (flags % 2) != 0;
      if (files_ && (signal != 0 || timed_any || (config_.checkpoint_every > 0 && step_ % config_.checkpoint_every == 0)))
        checkpoint();
      progress.update(step_ - first);
      if (signal != 0) {
        sum.stop_signal = static_cast<int>(signal);
        log(std::string("stopped by ") + StopSignal::name(sum.stop_signal) + " at step " + std::to_string(step_));
        break;
      }
    }
    if (files_ && config_.checkpoint_at_end && sum.stop_signal == 0 && checkpointed != step_) checkpoint();
  } catch (const InstabilityError& e) {
    progress.finish();
    log(std::string("FAILED: ") + e.what());
    throw;
  }
  progress.finish();
  sum.steps = step_ - first;
  sum.discs = n_discs;
  sum.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  sum.disc_steps_per_second = sum.wall_seconds > 0 ? sum.discs * sum.steps / sum.wall_seconds : 0.0;
  sum.dt = dt_;
  sum.critical = critical_;
  EnergyLedger g = global_ledger();
  sum.ledger_residual = g.relative_residual(kinetic_energy());
  sum.neighbour_builds = neighbours_.builds();
  std::ostringstream s;
  s << "summary: " << sum.steps << " steps of " << sum.discs << " discs in " << fmt(sum.wall_seconds, 4)
    << " s wall, " << fmt(sum.disc_steps_per_second, 4) << " disc-steps/s; dt " << fmt(dt_) << " s ("
    << fmt(dt_ / critical_.dt, 4) << " x critical, " << critical_.mode << " mode); ledger residual "
    << fmt(sum.ledger_residual, 3) << "; " << sum.neighbour_builds << " neighbour builds";
  log(s.str());
  const std::string final_state = write_files_ ? state_text() : "";
  if (write_files_ && comm_.root()) {
    std::ofstream(fs::path(config_.output) / "final.csv") << final_state;
    std::ofstream(fs::path(config_.output) / "summary.txt")
        << s.str() << (sum.stop_signal ? "\nstatus: stopped by a signal; resume with --resume " + config_.output + "\n"
                                       : std::string("\nstatus: complete\n"));
    log("results in " + config_.output + "/ (config.ini, log.txt, diagnostics.csv, measures.csv, final.csv, summary.txt" +
        (sum.last_checkpoint.empty() ? std::string(")") : ", checkpoint_*.h5)"));
  }
  return sum;
}

}  // namespace rondel
