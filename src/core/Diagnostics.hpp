#pragma once
#include <chrono>
#include <cstdint>
#include <fstream>
#include <string>

#include "core/LedgerTerms.hpp"

namespace rondel {

// A row of diagnostics.csv, with the run's ledger terms (their columns: LedgerTerms' work terms, E_stored,
// then its dissipation terms).
struct DiagnosticsRow : LedgerTerms {
  std::int64_t step = 0;
  double time = 0.0;
  double ke_trans = 0.0, ke_rot = 0.0;
  std::int64_t contacts = 0, wall_contacts = 0;
  double coordination = 0.0;    // 2 x disc-disc contacts / discs
  double max_overlap = 0.0;     // largest u_n / smaller radius
  double E_stored = 0.0;        // energy in the contact springs now
  double D_other = 0.0;         // -W_c - E_stored - the dissipation terms: dashpots and integration error
  double residual = 0.0;        // relative ledger residual
  double imbalance = 1.0;       // max over mean of the per-rank work at the last balance check
  double ghost_fraction = 0.0;  // ghosts over discs, all ranks
  std::int64_t migrated = 0;    // discs moved between ranks so far
  std::int64_t bonds = 0;       // intact parallel bonds (their breaks by mode: the ledger's counts)
};

// diagnostics.csv: one header, one row per diagnostics step (rank 0 only).
class DiagnosticsWriter {
 public:
  // Starts the file with its header, or appends to it (a resumed run) when `append` and it exists.
  void open(const std::string& path, bool append = false);
  void write(const DiagnosticsRow& row);
  // False once a write or flush failed (disk full): the file lacks rows.
  bool good() const { return !out_.is_open() || out_.good(); }
  // Every row written so far to the file; false when that failed.
  bool flush() {
    if (out_.is_open()) out_.flush();
    return good();
  }
  static std::string header();
  static std::string format(const DiagnosticsRow& row);

 private:
  std::ofstream out_;
  std::chrono::steady_clock::time_point last_flush_;
};

// A progress line with rate and ETA. On a terminal it is redrawn in place (at most four times a second);
// elsewhere (a pipe, a file, or under an MPI launcher) it is a plain line every `plain_seconds` and one at
// the end, never a carriage return.
class ProgressLine {
 public:
  ProgressLine(std::int64_t total_steps, std::int64_t n_discs, bool enabled, double plain_seconds = 10.0);
  void update(std::int64_t step);
  // Before another line is printed: a drawn line is erased (terminal) so the new one starts clean.
  void clear();
  // The last line, at `step` (the steps done), then a newline on a terminal.
  void finish(std::int64_t step);
  // Whether stdout is a terminal the line may redraw on. Under mpirun (Open MPI) every rank's stdout is a
  // pseudo-terminal whatever mpirun's own output is, so a launched process never counts as one.
  static bool stdout_is_terminal();

 private:
  void draw(std::int64_t step, std::chrono::steady_clock::time_point now);

  std::int64_t total_, discs_;
  bool enabled_, tty_;
  double plain_seconds_;
  bool drawn_ = false;           // a line is on the terminal, not yet ended by a newline
  std::int64_t last_step_ = -1;  // the step of the last line printed
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace rondel
