#include "app/Runner.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/Reports.hpp"
#include "app/RunFiles.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/StopSignal.hpp"
#include "parallel/Agreement.hpp"
#include "rondel/Version.hpp"

namespace rondel {

namespace {
double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}
}  // namespace

Runner::Runner(RunTarget& target) : sim_(target), files_(target.files()), phases_(target.phases()) {}

void Runner::log_start(std::int64_t n_discs) {
  const Config& config = sim_.state().config;
  const Communicator& comm = sim_.state().comm;
  const CriticalStep& critical = sim_.critical();
  files_.log(std::string("Rondel ") + kRondelVersion + " (commit " + kRondelCommit + "): " + std::to_string(n_discs) +
             " discs, " + std::to_string(sim_.state().walls.size()) + " walls, " + std::to_string(comm.size()) +
             " rank(s); laws: normal " + config.normal_law + ", tangential " + config.tangential_law + ", rolling " +
             config.rolling_law);
  if (Boundaries::any_rough(sim_.state().walls)) log_rough_walls();
  files_.log("time step " + fmt(sim_.state().dt) + " s = " + fmt(sim_.state().dt / critical.dt, 4) + " x critical " +
             fmt(critical.dt) + " s, limited by the " + critical.mode + " mode (" + critical.pair + ")");
  files_.log("neighbour skin " + fmt(sim_.counts().skin) + " m; output in " +
             (files_.has_directory() ? config.output + " (resolved configuration in config.ini and log.txt)"
                                     : std::string("(none)")) +
             (sim_.state().step > 0 ? "; resumed at step " + std::to_string(sim_.state().step) : ""));
  // The resolved configuration is long (every key): log.txt and config.ini keep it, the terminal does not.
  files_.log_file_only("resolved configuration:\n" + config.resolved_text);
}

void Runner::log_rough_walls() {
  const WallSet& walls = sim_.state().walls;
  const std::vector<std::int64_t> glued = Boundaries::glued_counts(sim_.state().discs, walls.size());
  std::string line = "rough walls:";
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (!walls[w].rough) continue;
    const std::int64_t n = sim_.state().comm.sum(glued[w]);
    line +=
        " wall " + std::to_string(w) + " carries " + std::to_string(n) + " glued discs" +
        (n == 0 ? " (warning: none; glue happens at the start of a stage, within walls.rough_depth of the wall)" : "") +
        ";";
  }
  files_.log(line.substr(0, line.size() - 1));
}

void Runner::record() {
  // The rows are computed collectively; rank 0 writes them, agreed (a full disk stops every rank).
  const Communicator& comm = sim_.state().comm;
  const DiagnosticsRow row = sim_.diagnostics();
  agree(comm, [&] {
    files_.write_diagnostics(row);
    const std::int64_t every = sim_.state().config.thermo_every;
    if (every > 0 && (row.step % every == 0 || row.step == sim_.state().config.steps)) thermo(row);
    files_.check_log();
  });
  // From the global row: every rank alike (its message calls collectives), agreed so that it is printed once.
  agree(comm, [&] { Reports(sim_.state()).check_stability(row, d_other_peak_); });
  if (!files_.has_directory()) return;
  const MeasuresRow m = sim_.measures(sim_.last_contacts());
  agree(comm, [&] { files_.write_measures(m); });
}

void Runner::thermo(const DiagnosticsRow& row) {
  // From the diagnostics row of this step: no reduction of its own. The rate is over the steps since the
  // previous thermo line.
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - thermo_clock_).count();
  const double rate = thermo_step_ >= 0 && seconds > 0.0 ? (row.step - thermo_step_) / seconds : 0.0;
  char line[256];
  if (thermo_step_ < 0) {
    std::snprintf(line, sizeof line, "%10s %12s %12s %9s %9s %10s", "step", "time[s]", "KE[J]", "contacts", "residual",
                  "steps/s");
    files_.log(line);
  }
  std::snprintf(line, sizeof line, "%10lld %12.5g %12.5g %9lld %9.2e %10.3g", static_cast<long long>(row.step),
                row.time, row.ke_trans + row.ke_rot, static_cast<long long>(row.contacts + row.wall_contacts),
                row.residual, rate);
  files_.log(line);
  thermo_step_ = row.step;
  thermo_clock_ = now;
}

std::string Runner::checkpoint() {
  files_.add_wall_seconds(seconds_since(last_checkpoint_));
  last_checkpoint_ = std::chrono::steady_clock::now();
  // The tables' rows up to this step reach their files first: a run killed after the checkpoint and resumed
  // from it then finds every row up to the checkpoint's step (and RunFiles::prepare cuts the later ones).
  agree(sim_.state().comm, [&] { files_.flush_tables(); });
  agree(sim_.state().comm, [&] {
    sum_.last_checkpoint = sim_.write_checkpoint();
    files_.check_log();
  });
  checkpointed_ = sim_.state().step;
  return sum_.last_checkpoint;
}

void Runner::snapshot() {
  agree(sim_.state().comm, [&] { sim_.write_snapshot(); });
}

std::int64_t Runner::stop_flags() {
  // This rank's stop request; the ranks agree on the step of a signal or of a wall-clock checkpoint in the
  // step's reduction (rank 0's clock decides).
  const Config& config = sim_.state().config;
  const Communicator& comm = sim_.state().comm;
  const double minutes = seconds_since(last_checkpoint_) / 60.0;
  const bool timed = comm.root() && config.checkpoint_minutes > 0.0 && minutes >= config.checkpoint_minutes;
  // Both ride in the step's reduction (Simulation::request_stop): the signal number times 2, plus 1 for a
  // due wall-clock checkpoint; a step without a reduction acts on them at the next one.
  return 2 * static_cast<std::int64_t>(StopSignal::received()) + (timed ? 1 : 0);
}

int Runner::loop(std::int64_t end) {
  const Config& config = sim_.state().config;
  // The steps up to the next one that something looks at (diagnostics, a snapshot, a checkpoint, the end)
  // run as one advance (Simulation::advance: a pass over the discs less per step); a stop agreed in a step's
  // reduction ends it early.
  const auto next_multiple = [](std::int64_t step, std::int64_t every) { return (step / every + 1) * every; };
  while (sim_.state().step < end) {
    const std::int64_t now = sim_.state().step;
    std::int64_t until = std::min(end, next_multiple(now, config.diag_every));
    if (now < config.steps) until = std::min(until, config.steps);  // run.steps has its row (a driver steps past it)
    if (files_.has_directory() && config.snapshot_every > 0)
      until = std::min(until, next_multiple(now, config.snapshot_every));
    if (files_.has_directory() && config.checkpoint_every > 0)
      until = std::min(until, next_multiple(now, config.checkpoint_every));
    sim_.advance_steps(until - now, [&] {
      progress_->update(sim_.state().step - first_);
      return stop_flags();
    });
    const std::int64_t step = sim_.state().step;
    phases_.restart();
    if (step % config.diag_every == 0 || step == config.steps) record();
    if (files_.has_directory() && config.snapshot_every > 0 && step % config.snapshot_every == 0) snapshot();
    phases_.lap(PhaseTimes::output);
    const std::int64_t flags = sim_.agreed_stop();
    const std::int64_t signal = flags / 2;
    const bool timed_any = (flags % 2) != 0;
    if (files_.has_directory() &&
        (signal != 0 || timed_any || (config.checkpoint_every > 0 && step % config.checkpoint_every == 0)))
      checkpoint();
    phases_.lap(PhaseTimes::output);
    progress_->update(step - first_);
    phases_.lap(PhaseTimes::other);
    if (signal != 0) {
      files_.log(std::string("stopped by ") + StopSignal::name(static_cast<int>(signal)) + " at step " +
                 std::to_string(step));
      return static_cast<int>(signal);
    }
  }
  return 0;
}

Runner::~Runner() {
  if (progress_) files_.set_progress(nullptr);
}

void Runner::failed(const std::exception& e) {
  // An instability, an I/O error: log.txt says so (rank 0).
  progress_->finish(sim_.state().step - first_);
  files_.set_progress(nullptr);
  files_.log(std::string("FAILED: ") + e.what());
  throw;
}

void Runner::start() {
  n_discs_ = sim_.state().comm.sum(static_cast<std::int64_t>(sim_.state().discs.n_owned()));
  log_start(n_discs_);
  const Config& config = sim_.state().config;
  first_ = sim_.state().step;
  const std::int64_t remaining = std::max<std::int64_t>(0, config.steps - first_);
  progress_ = std::make_unique<ProgressLine>(remaining, n_discs_,
                                             files_.has_directory() && config.progress && sim_.state().comm.root());
  files_.set_progress(progress_.get());
  StopSignal::install();
  start_ = last_checkpoint_ = thermo_clock_ = std::chrono::steady_clock::now();
  at_start_ = phases_;
  try {
    phases_.restart();
    if (first_ == 0) record();
    if (first_ == 0 && files_.has_directory() && config.snapshot_every > 0) snapshot();  // the initial state
    phases_.lap(PhaseTimes::output);
  } catch (const std::exception& e) {
    failed(e);
  }
}

int Runner::advance(std::int64_t n) {
  try {
    const int signal = loop(sim_.state().step + n);
    if (signal != 0) sum_.stop_signal = signal;
    return signal;
  } catch (const std::exception& e) {
    failed(e);
  }
}

RunSummary Runner::run() {
  start();
  const std::int64_t remaining = sim_.state().config.steps - sim_.state().step;
  if (remaining > 0) advance(remaining);
  return finish();
}

RunSummary Runner::finish() {
  const Config& config = sim_.state().config;
  try {
    sim_.settle_errors();  // a rank's error found since the last reduction stops the run here
    if (files_.has_directory() && config.checkpoint_at_end && sum_.stop_signal == 0 &&
        checkpointed_ != sim_.state().step)
      checkpoint();
    phases_.lap(PhaseTimes::output);
  } catch (const std::exception& e) {
    failed(e);
  }
  progress_->finish(sim_.state().step - first_);
  files_.set_progress(nullptr);
  summarise();
  return sum_;
}

void Runner::summarise() {
  const std::int64_t first = first_, n_discs = n_discs_;
  const PhaseTimes& at_start = at_start_;
  const CriticalStep& critical = sim_.critical();
  const double dt = sim_.state().dt;
  RunSummary& sum = sum_;
  sum.steps = sim_.state().step - first;
  sum.discs = n_discs;
  sum.wall_seconds = seconds_since(start_);
  sum.disc_steps_per_second = sum.wall_seconds > 0 ? sum.discs * sum.steps / sum.wall_seconds : 0.0;
  sum.dt = dt;
  sum.critical = critical;
  const Reports reports(sim_.state());
  EnergyLedger g = reports.global_ledger();
  sum.ledger_residual = g.relative_residual(reports.kinetic_energy());
  sum.neighbour_builds = sim_.counts().neighbour_builds;
  std::ostringstream s;
  s << "summary: " << sum.steps << " steps of " << sum.discs << " discs in " << fmt(sum.wall_seconds, 4) << " s wall, "
    << fmt(sum.disc_steps_per_second, 4) << " disc-steps/s; dt " << fmt(dt) << " s (" << fmt(dt / critical.dt, 4)
    << " x critical, " << critical.mode << " mode); ledger residual " << fmt(sum.ledger_residual, 3) << "; "
    << sum.neighbour_builds << " neighbour builds";
  if (sim_.state().comm.size() > 1 && sim_.counts().steps_taken > 0) {
    // What the steps asked of MPI, largest rank (docs/scaling.md): at most one collective per step.
    const Communicator& comm = sim_.state().comm;
    const CommStats& c = sim_.counts().step_comm;
    const auto per_step = [&](std::int64_t v) {
      return static_cast<double>(comm.max(v)) / static_cast<double>(sim_.counts().steps_taken);
    };
    sum.collectives_per_step = per_step(c.collectives);
    sum.messages_per_step = per_step(c.messages);
    s << "; per step and rank " << fmt(sum.collectives_per_step, 3) << " collectives, " << fmt(sum.messages_per_step, 3)
      << " messages";
  }
  files_.log(s.str());
  const std::string phases = phases_.line_since(at_start) + " (rank 0)";
  files_.log(phases);
  if (!files_.has_directory()) return;
  const std::string output = sim_.state().config.output;
  agree(sim_.state().comm, [&] {
    files_.flush_tables();
    files_.check_log();
  });
  sim_.write_final(files_.final_path());  // every rank its block, in gid order (agreed inside)
  agree(sim_.state().comm, [&] {
    files_.write_results(s.str() + "\n" + phases, summary_json(at_start_), sum.stop_signal != 0);
    files_.log("results in " + output +
               "/ (config.ini, log.txt, diagnostics.csv, measures.csv, final.csv, summary.txt, summary.json" +
               (sum.last_checkpoint.empty() ? std::string(")") : ", checkpoint_*.h5)"));
    files_.check_log();
  });
}

std::string Runner::summary_json(const PhaseTimes& at_start) const {
  // Numbers with 17 significant digits (they read back to the same doubles); strings escaped. The caller
  // adds the list of output files and the closing brace.
  const auto num = [](double v) { return std::isfinite(v) ? fmt(v, 17) : std::string("null"); };
  const auto str = [](const std::string& v) {
    std::string out = "\"";
    for (const char c : v) {
      if (c == '"' || c == '\\')
        (out += '\\') += c;
      else if (static_cast<unsigned char>(c) < 0x20)
        out += ' ';
      else
        out += c;
    }
    return out + '"';
  };
  const RunSummary& m = sum_;
  std::ostringstream j;
  j << "{\n  \"status\": " << str(m.stop_signal != 0 ? "stopped" : "complete")
    << ",\n  \"stop_signal\": " << (m.stop_signal != 0 ? str(StopSignal::name(m.stop_signal)) : "null")
    << ",\n  \"rondel_version\": " << str(kRondelVersion) << ",\n  \"rondel_commit\": " << str(kRondelCommit)
    << ",\n  \"steps\": " << m.steps << ",\n  \"final_step\": " << sim_.state().step << ",\n  \"discs\": " << m.discs
    << ",\n  \"ranks\": " << sim_.state().comm.size() << ",\n  \"wall_seconds\": " << num(m.wall_seconds)
    << ",\n  \"disc_steps_per_second\": " << num(m.disc_steps_per_second) << ",\n  \"dt\": " << num(m.dt)
    << ",\n  \"critical_dt\": " << num(m.critical.dt) << ",\n  \"critical_mode\": " << str(m.critical.mode)
    << ",\n  \"critical_pair\": " << str(m.critical.pair) << ",\n  \"ledger_residual\": " << num(m.ledger_residual)
    << ",\n  \"neighbour_builds\": " << m.neighbour_builds
    << ",\n  \"collectives_per_step\": " << num(m.collectives_per_step)
    << ",\n  \"messages_per_step\": " << num(m.messages_per_step) << ",\n  \"phase_seconds_rank0\": {";
  for (int p = 0; p < PhaseTimes::count; ++p) {
    const auto phase = static_cast<PhaseTimes::Phase>(p);
    j << (p ? ", " : "") << str(PhaseTimes::name(phase)) << ": "
      << num(phases_.seconds(phase) - at_start.seconds(phase));
  }
  j << "},\n  \"last_checkpoint\": " << (m.last_checkpoint.empty() ? "null" : str(m.last_checkpoint));
  return j.str();
}

}  // namespace rondel
