#include "core/Diagnostics.hpp"

#include <unistd.h>

#include <cstdio>
#include <sstream>

namespace rondel {

std::string DiagnosticsWriter::header() {
  return "step,time,ke_trans,ke_rot,contacts,wall_contacts,coordination,max_overlap_ratio,W_gravity,W_walls,"
         "W_normal,W_tangential,W_rolling,E_stored,D_slip,D_rolling_plastic,D_rolling_dashpot,E_rolling_break,D_other,"
         "ledger_residual,imbalance,ghost_fraction,migrated";
}

std::string DiagnosticsWriter::format(const DiagnosticsRow& r) {
  std::ostringstream s;
  s.precision(12);
  s << r.step << ',';
  s.precision(16);
  s << r.time << ',';
  s.precision(12);
  s << r.ke_trans << ',' << r.ke_rot << ',' << r.contacts << ','
    << r.wall_contacts << ',' << r.coordination << ',' << r.max_overlap << ',' << r.W_g << ',' << r.W_w << ','
    << r.W_n << ',' << r.W_t << ',' << r.W_r << ',' << r.E_stored << ',' << r.D_slip << ',' << r.D_r_plastic << ','
    << r.D_r_dashpot << ',' << r.E_r_break << ',' << r.D_other << ',' << r.residual << ',' << r.imbalance << ',' << r.ghost_fraction << ',' << r.migrated;
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
    : total_(total_steps), discs_(n_discs), enabled_(enabled), tty_(isatty(STDOUT_FILENO) != 0),
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
              static_cast<long long>(step), static_cast<long long>(total_), 100.0 * step / total_, rate,
              rate * discs_, eta, tty_ ? "   " : "\n");
  std::fflush(stdout);
  next_plain_ = step + std::max<std::int64_t>(1, total_ / 10);
}

void ProgressLine::finish() {
  if (enabled_ && tty_) std::printf("\n");
}

}  // namespace rondel
