#include "core/Diagnostics.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace rondel {

// The ledger's columns: its work terms, E_stored, then its dissipation terms (LedgerTerms' order); its counts last.
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
  h += ",D_other,ledger_residual,imbalance,ghost_fraction,migrated,bonds";
  names(kTermCount);
  return h;
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
  s << ',' << r.D_other << ',' << r.residual << ',' << r.imbalance << ',' << r.ghost_fraction << ',' << r.migrated
    << ',' << r.bonds;
  values(kTermCount);
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

ProgressLine::ProgressLine(std::int64_t total_steps, std::int64_t n_discs, bool enabled, double plain_seconds)
    : total_(total_steps),
      discs_(n_discs),
      enabled_(enabled && total_steps > 0),
      tty_(stdout_is_terminal()),
      plain_seconds_(plain_seconds),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

bool ProgressLine::stdout_is_terminal() {
  // Set by mpirun (Open MPI) and by MPICH's launcher; not by an MPI singleton (PMIX_RANK is, so it is no sign).
  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launcher) != nullptr) return false;
  return isatty(STDOUT_FILENO) != 0;
}

void ProgressLine::update(std::int64_t step) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  if (tty_ ? since < 0.25 : since < plain_seconds_) return;
  draw(step, now);
}

void ProgressLine::draw(std::int64_t step, std::chrono::steady_clock::time_point now) {
  last_draw_ = now;
  last_step_ = step;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? step / elapsed : 0.0;
  const double eta = rate > 0 ? (total_ - step) / rate : 0.0;
  char line[200];
  std::snprintf(line, sizeof line, "step %lld/%lld (%3.0f%%)  %.3g steps/s  %.3g disc-steps/s  ETA %.0f s",
                static_cast<long long>(step), static_cast<long long>(total_), 100.0 * step / total_, rate,
                rate * discs_, eta);
  if (tty_) {
    std::printf("\r%s\033[K", line);  // \033[K erases what a longer earlier line left
    drawn_ = true;
  } else {
    std::printf("%s\n", line);
  }
  std::fflush(stdout);
}

void ProgressLine::clear() {
  if (!drawn_) return;
  std::printf("\r\033[K");
  std::fflush(stdout);
  drawn_ = false;
}

void ProgressLine::finish(std::int64_t step) {
  if (!enabled_) return;
  if (last_step_ != step) draw(step, std::chrono::steady_clock::now());
  if (tty_ && drawn_) std::printf("\n");
  drawn_ = false;
  std::fflush(stdout);
}

}  // namespace rondel
