#pragma once
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "app/Measures.hpp"
#include "app/PhaseTimes.hpp"
#include "app/RunState.hpp"
#include "core/Diagnostics.hpp"
#include "parallel/Communicator.hpp"
#include "physics/ContactPass.hpp"
#include "physics/CriticalTimeStep.hpp"

namespace rondel {

class RunFiles;
class ProgressLine;

struct RunSummary {
  int stop_signal = 0;          // the signal that stopped the run early (0: it ran to the end)
  std::string last_checkpoint;  // path of the last checkpoint written ("" if none)
  std::int64_t steps = 0;
  std::int64_t discs = 0;
  double wall_seconds = 0.0;
  double disc_steps_per_second = 0.0;
  double dt = 0.0;
  CriticalStep critical;
  double ledger_residual = 0.0;
  std::size_t neighbour_builds = 0;
  double collectives_per_step = 0.0, messages_per_step = 0.0;  // the steps', largest rank (several ranks)
};

// The counts a run's summary reports.
struct RunCounts {
  double skin = 0.0;                 // the neighbour list's skin [m]
  std::size_t neighbour_builds = 0;  // so far
  std::int64_t steps_taken = 0;      // by this object's steps
  CommStats step_comm;               // what those steps asked of MPI, on this rank
};

// What a Runner drives (Simulation is one): the steps, the outputs and a view of the state. Collective where a
// Simulation's function of the same name is.
class RunTarget {
 public:
  virtual ~RunTarget() = default;
  virtual RunState state() const = 0;
  virtual const CriticalStep& critical() const = 0;
  virtual RunCounts counts() const = 0;
  virtual RunFiles& files() = 0;
  virtual PhaseTimes& phases() = 0;
  // Up to n steps that nothing looks at in between; stop_flags() before each gives this rank's stop request.
  virtual std::int64_t advance_steps(std::int64_t n, const std::function<std::int64_t()>& stop_flags) = 0;
  virtual std::int64_t agreed_stop() const = 0;
  virtual void settle_errors() = 0;
  virtual DiagnosticsRow diagnostics() = 0;
  virtual const ContactSummary& last_contacts() const = 0;
  virtual MeasuresRow measures(const ContactSummary& contacts) = 0;
  virtual std::string write_checkpoint() = 0;
  virtual void write_snapshot() = 0;
  virtual void write_final(const std::string& path) const = 0;
};

// The run of a RunTarget to run.steps: the opening log lines, the time loop with the schedules of
// diagnostics, measures, snapshots and checkpoints, the signals (every rank agrees on the step of a stop),
// the progress and thermo lines, and the summary with its phase times (log.txt, summary.txt, summary.json,
// final.csv).
//
// A run to run.steps is run(); a driver that steps in its own chunks (the Python module) calls start(), then
// advance() as often as it likes, then finish(): the same schedules, files and bits.
class Runner {
 public:
  explicit Runner(RunTarget& target);
  ~Runner();
  RunSummary run();
  // The opening log lines and, at step 0, the first diagnostics row and snapshot.
  void start();
  // n steps (past run.steps too) with the schedules of diagnostics, snapshots and checkpoints; returns the
  // signal that stopped them after its checkpoint (0: none).
  int advance(std::int64_t n);
  // The end of the run: the pending errors, the checkpoint at the end, the summary and final.csv.
  RunSummary finish();
  bool started() const { return progress_ != nullptr; }
  // Collective and agreed, like every output of the run: an error on one rank stops every rank. A checkpoint
  // comes after the tables' rows up to its step; returns its path.
  std::string checkpoint();
  void snapshot();

 private:
  void log_start(std::int64_t n_discs);
  void log_rough_walls();
  // The thermo line of a diagnostics row (and its column header before the first one).
  void thermo(const DiagnosticsRow& row);
  // summary.json without the list of output files and the closing brace (RunFiles adds them).
  std::string summary_json(const PhaseTimes& at_start) const;
  // Diagnostics and measures of the present step, and the stability check.
  void record();
  // One reduction: the signal received on any rank, and whether rank 0's clock says a checkpoint is due.
  std::int64_t stop_flags();
  // The steps up to `end`; returns the signal that stopped them (0: none).
  int loop(std::int64_t end);
  // The log of a failure (rank 0), then the error again.
  [[noreturn]] void failed(const std::exception& e);
  void summarise();

  RunTarget& sim_;
  RunFiles& files_;
  PhaseTimes& phases_;
  RunSummary sum_;
  std::chrono::steady_clock::time_point start_, last_checkpoint_, thermo_clock_;
  std::int64_t thermo_step_ = -1;    // the step of the last thermo line (-1: none yet)
  double d_other_peak_ = -HUGE_VAL;  // the largest D_other of this run's diagnostics rows (Reports::check_stability)
  std::int64_t checkpointed_ = -1;
  std::int64_t first_ = 0, n_discs_ = 0;  // the step and the discs at start()
  PhaseTimes at_start_;
  std::unique_ptr<ProgressLine> progress_;  // from start()
};

}  // namespace rondel
