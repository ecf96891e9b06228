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
};

// diagnostics.csv: one header, one row per diagnostics step (rank 0 only).
class DiagnosticsWriter {
 public:
  // Starts the file with its header, or appends to it (a resumed run) when `append` and it exists.
  void open(const std::string& path, bool append = false);
  void write(const DiagnosticsRow& row);
  static std::string header();
  static std::string format(const DiagnosticsRow& row);

 private:
  std::ofstream out_;
  std::chrono::steady_clock::time_point last_flush_;
};

// A progress line with rate and ETA: rewritten in place on a terminal, a plain line every tenth of the run
// otherwise.
class ProgressLine {
 public:
  ProgressLine(std::int64_t total_steps, std::int64_t n_discs, bool enabled);
  void update(std::int64_t step);
  void finish();

 private:
  std::int64_t total_, discs_;
  bool enabled_, tty_;
  std::int64_t next_plain_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace rondel
