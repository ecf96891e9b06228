#include "core/Diagnostics.hpp"

#include <unistd.h>

#include <cstdio>
#include <sstream>

namespace rondel {

// The ledger's columns: its work terms, E_stored, then its dissipation terms (LedgerTerms' order).
std::string DiagnosticsWriter::header() {
  std::string h = "step,time,ke_trans,ke_rot,contacts,wall_contacts,coordination,max_overlap_ratio";
  const auto names = [&h](unsigned use) {
    LedgerTerms{}.for_each_term([&](const LedgerTermInfo& t, double) {
      if (t.uses & use) (h += ',') += t.column;
    });
  };
  names(kTermWork);
  h += ",E_stored";
  names(kTermDissipation);
  return h + ",D_other,ledger_residual,imbalance,ghost_fraction,migrated";
}

std::string DiagnosticsWriter::format(const DiagnosticsRow& r) {
  std::ostringstream s;
  const auto values = [&](unsigned use) {
    r.for_each_term([&](const LedgerTermInfo& t, double v) {
      if (t.uses & use) s << ',' << v;
    });
  };
  s.precision(12);
  s << r.step << ',';
  s.precision(16);
  s << r.time << ',';
  s.precision(12);
  s << r.ke_trans << ',' << r.ke_rot << ',' << r.contacts << ',' << r.wall_contacts << ',' << r.coordination << ','
    << r.max_overlap;
  values(kTermWork);
  s << ',' << r.E_stored;
  values(kTermDissipation);
  s << ',' << r.D_other << ',' << r.residual << ',' << r.imbalance << ',' << r.ghost_fraction << ',' << r.migrated;
  return s.str();
}

void DiagnosticsWriter::open(const std::string& path, bool append) {
  const bool existed = append && std::ifstream(path).good();
  out_.open(path, append ? std::ios::app : std::ios::trunc);
  if (!existed) out_ << header() << '\n';
}

void DiagnosticsWriter::write(const DiagnosticsRow& row) {
  if (!out_.is_open()) return;
  out_ << format(row) << '\n';
  // Flushed at most once a second: a crash keeps nearly everything, without a flush per row.
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ > std::chrono::seconds(1)) {
    out_.flush();
    last_flush_ = now;
  }
}

ProgressLine::ProgressLine(std::int64_t total_steps, std::int64_t n_discs, bool enabled)
    : total_(total_steps),
      discs_(n_discs),
      enabled_(enabled),
      tty_(isatty(STDOUT_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

void ProgressLine::update(std::int64_t step) {
  if (!enabled_ || total_ <= 0) return;
  if (!tty_ && step < next_plain_) return;
  const auto now = std::chrono::steady_clock::now();
  // On a terminal the line is redrawn at most four times a second (mpirun forwards output through a pty).
  if (tty_ && step != total_ && now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? step / elapsed : 0.0;
  const double eta = rate > 0 ? (total_ - step) / rate : 0.0;
  std::printf("%sstep %lld/%lld (%3.0f%%)  %.3g steps/s  %.3g disc-steps/s  ETA %.0f s%s", tty_ ? "\r" : "",
              static_cast<long long>(step), static_cast<long long>(total_), 100.0 * step / total_, rate, rate * discs_,
              eta, tty_ ? "   " : "\n");
  std::fflush(stdout);
  next_plain_ = step + std::max<std::int64_t>(1, total_ / 10);
}

void ProgressLine::finish() {
  if (enabled_ && tty_) std::printf("\n");
}

}  // namespace rondel
