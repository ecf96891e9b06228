// The output directory of a run and its files (docs/design.md section 7, FORMAT.md).
#include "app/RunFiles.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <random>

#include "app/OutputNames.hpp"
#include "core/Errors.hpp"
#include "core/FaultInjection.hpp"
#include "parallel/Agreement.hpp"

namespace rondel {

namespace fs = std::filesystem;

namespace {

// Whether `a` and `b` name the same existing directory.
bool same_directory(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// Whether process `pid` runs on this host: it exists and is not a zombie (a killed process that its parent
// has not reaped yet holds nothing open any more).
bool process_runs(long pid) {
  if (pid <= 0 || (::kill(static_cast<pid_t>(pid), 0) != 0 && errno != EPERM)) return false;
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return true;  // no /proc: trust kill()
  const auto paren = line.rfind(')');
  return paren == std::string::npos || paren + 2 >= line.size() || line[paren + 2] != 'Z';
}

// Rank 0: cuts a resumed run's table (diagnostics.csv, measures.csv: the step in the first column) back to the
// rows of steps up to `step`, so that the rows the interrupted run wrote after its checkpoint are not there
// twice. The header and any line that does not start with a step are kept. Written to a temporary file
// and renamed over the table, so a failure leaves the table as it was.
void cut_table(const fs::path& path, std::int64_t step) {
  std::ifstream in(path);
  if (!in) return;
  std::string kept, line;
  bool cut = false;
  while (std::getline(in, line)) {
    char* end = nullptr;
    const long long row_step = std::strtoll(line.c_str(), &end, 10);
    const bool row = end != line.c_str() && (*end == ',' || *end == '\0');
    if (row && row_step > step) {
      cut = true;
      continue;
    }
    kept += line;
    kept += '\n';
  }
  if (!in.eof()) throw IoError("cannot read '" + path.string() + "' to resume it");
  in.close();
  if (!cut) return;
  const fs::path part = path.string() + ".part";
  std::ofstream out(part, std::ios::trunc);
  out << kept;
  out.flush();
  out.close();
  std::error_code ec;
  if (out.fail()) {
    fs::remove(part, ec);
    throw IoError("cannot write '" + part.string() + "' (disk full, permissions?) to cut '" + path.string() +
                  "' back to step " + std::to_string(step));
  }
  fs::rename(part, path, ec);
  if (ec) throw IoError("cannot replace '" + path.string() + "': " + ec.message());
}

// Whether writing the text file `path` failed: `ok` false, or a fault injected for it (core/FaultInjection.hpp).
bool failed(bool ok, const fs::path& path) {
  return !ok || injected_fault(FaultSite::text, 0, path.filename().string());
}

}  // namespace

RunFiles::~RunFiles() {
  if (lock_.empty()) return;
  std::error_code ec;
  fs::remove(lock_, ec);
}

void RunFiles::prepare(const std::string& checkpoint, std::int64_t step) {
  // Rank 0 looks at the directory and creates it; every step that only rank 0 does is agreed, so that its
  // error (a directory in use, a file it cannot write) stops every rank.
  const bool resuming = !checkpoint.empty();
  agree(comm_, [&] { claim_directory(checkpoint); });
  checkpoints_ = std::make_unique<Checkpointing>(config_.output, config_.checkpoint_keep, config_.verify_checkpoints,
                                                 config_.snapshot_fields, config_.domain, comm_);
  if (resuming)
    agree(comm_, [&] { checkpoints_->adopt_snapshots(step); });
  else
    agree(comm_, [&] { checkpoints_->remove_old_files(); });
  agree(comm_, [&] { open_files(resuming, step); });
}

void RunFiles::claim_directory(const std::string& checkpoint) {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  const bool exists = fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir));
  // A resumed run continues in the directory of its checkpoint; another directory must be new (or given up).
  const bool own = !checkpoint.empty() && same_directory(fs::path(checkpoint).parent_path(), dir);
  if (exists && !config_.overwrite && !own)
    throw ConfigError("run.output = '" + config_.output + "' already exists and is not empty" +
                      (checkpoint.empty() ? std::string()
                                          : " (and it is not the directory of the run being resumed, '" +
                                                fs::path(checkpoint).parent_path().string() + "')") +
                      "; choose another directory or set run.overwrite = true");
  std::error_code ec;
  fs::create_directories(dir, ec);
  take_lock(dir);
  if (!std::ofstream(dir / output::kConfig).good())
    throw ConfigError("run.output = '" + config_.output + "' cannot be written (permissions, or a file of that name)");
}

void RunFiles::take_lock(const fs::path& dir) {
  // The lock file holds "PID HOST" of rank 0. Created exclusively; one left by a process that no longer runs
  // on this host (a run killed with SIGKILL) is taken over.
  char host[256] = {};
  gethostname(host, sizeof host - 1);
  const fs::path path = dir / output::kLock;
  for (int attempt = 0; attempt < 2; ++attempt) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      const std::string text = std::to_string(getpid()) + " " + host + "\n";
      const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
      ::close(fd);
      lock_ = path;
      if (!ok) throw IoError("cannot write the lock file '" + path.string() + "' (disk full?)");
      return;
    }
    if (errno != EEXIST)
      throw ConfigError("run.output = '" + config_.output + "' cannot be written: cannot create the lock file '" +
                        path.string() + "': " + std::strerror(errno));
    long pid = 0;
    std::string owner_host;
    std::ifstream(path) >> pid >> owner_host;
    const bool alive = owner_host == host && process_runs(pid);
    const bool elsewhere = pid > 0 && owner_host != host;
    if (alive || (elsewhere && !config_.take_lock) || attempt > 0)
      throw ConfigError("run.output = '" + config_.output + "' is in use by another run (process " +
                        std::to_string(pid) + " on " + (owner_host.empty() ? std::string("?") : owner_host) +
                        ", lock file '" + path.string() + "'); wait for it to end" +
                        (elsewhere ? ", or, if that run is gone (its node failed), rerun with --run.take_lock=true"
                                   : ", or remove the lock file if no run uses the directory"));
    std::error_code ec;
    fs::remove(path, ec);  // stale: its process is gone
  }
}

void RunFiles::open_files(bool resuming, std::int64_t step) {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  std::error_code ec;
  for (const char* stale : {output::kFinal, output::kSummaryText, output::kSummaryJson}) fs::remove(dir / stale, ec);
  if (resuming) {
    cut_table(dir / output::kDiagnostics, step);
    cut_table(dir / output::kMeasures, step);
  }
  std::ofstream config(dir / output::kConfig);
  config << "# resolved configuration of this run (every key, defaults included)\n"
         << output::kRunIdComment << config_.run_id << '\n'
         << config_.resolved_text;
  close_checked(config, dir / output::kConfig);
  log_.open(dir / output::kLog, resuming ? std::ios::app : std::ios::trunc);
  check_stream(log_, dir / output::kLog);
  diag_.open((dir / output::kDiagnostics).string(), resuming);
  const bool measures_existed = resuming && fs::exists(dir / output::kMeasures);
  measures_.open(dir / output::kMeasures, resuming ? std::ios::app : std::ios::trunc);
  if (!measures_existed) measures_ << MeasuresRow::header() << '\n';
  check_stream(measures_, dir / output::kMeasures);
}

std::string RunFiles::new_run_id(const Communicator& comm) {
  std::vector<char> id;
  if (comm.root()) {
    std::random_device device;
    char text[40];
    std::snprintf(text, sizeof text, "%08x%08x%08x%08x", device(), device(), device(), device());
    id.assign(text, text + 32);
  }
  if (comm.size() > 1) comm.broadcast(id);
  return std::string(id.begin(), id.end());
}

std::string RunFiles::write_failure(const fs::path& path) {
  return "cannot write '" + path.string() + "' (disk full, permissions, or a removed directory)";
}

void RunFiles::write_failed(const fs::path& path) { throw IoError(write_failure(path)); }

void RunFiles::check_stream(const std::ostream& out, const fs::path& path) {
  if (failed(out.good(), path)) write_failed(path);
}

void RunFiles::close_checked(std::ofstream& out, const fs::path& path) {
  out.flush();
  const bool written = !failed(out.good(), path);
  out.close();
  if (!written || out.fail()) {
    std::error_code ec;
    fs::remove(path, ec);  // not left to be taken for the whole file
    write_failed(path);
  }
}

void RunFiles::check_log() {
  if (!log_failed_.empty()) throw IoError(log_failed_);
}

void RunFiles::log(const std::string& line) {
  if (!comm_.root()) return;
  if (write_files_) {
    if (progress_) progress_->clear();
    std::cout << line << '\n' << std::flush;
  }
  log_file_only(line);
}

void RunFiles::log_file_only(const std::string& line) {
  // Called from anywhere, also between collectives: a failure is kept and raised at the next agreed output
  // step (check_log), not here.
  if (!comm_.root() || !log_.is_open()) return;
  log_ << line << '\n' << std::flush;
  if (!log_.good() && log_failed_.empty()) log_failed_ = write_failure(fs::path(config_.output) / output::kLog);
}

void RunFiles::write_diagnostics(const DiagnosticsRow& row) {
  if (!comm_.root()) return;
  diag_.write(row);
  if (failed(diag_.good(), fs::path(config_.output) / output::kDiagnostics))
    write_failed(fs::path(config_.output) / output::kDiagnostics);
}

void RunFiles::write_measures(const MeasuresRow& row) {
  if (!comm_.root() || !measures_.is_open()) return;
  measures_ << row.csv() << '\n';
  check_stream(measures_, fs::path(config_.output) / output::kMeasures);
}

std::string RunFiles::write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                                       const ContactTable& wall_rows, const WallSet& walls, const StateExtras& extras) {
  const std::string path =
      checkpoints_->write_checkpoint(header, discs, pairs, wall_rows, walls, wall_seconds_, extras);
  log("checkpoint at step " + std::to_string(header.step) + ": " + path);
  return path;
}

void RunFiles::write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls, std::int64_t n_discs,
                              const StateExtras& extras) {
  checkpoints_->write_snapshot(header, discs, walls, n_discs, extras);
}

void RunFiles::flush_tables() {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  // The rows of diagnostics.csv and measures.csv reach their files (the writers flush them once a second).
  if (failed(diag_.flush(), dir / output::kDiagnostics)) write_failed(dir / output::kDiagnostics);
  if (measures_.is_open()) check_stream(measures_.flush(), dir / output::kMeasures);
}

std::string RunFiles::final_path() const { return (fs::path(config_.output) / output::kFinal).string(); }

void RunFiles::write_results(const std::string& summary, const std::string& json, bool stopped) {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  std::ofstream summary_txt(dir / output::kSummaryText);
  summary_txt << summary
              << (stopped ? "\nstatus: stopped by a signal; resume with --resume " + config_.output + "\n"
                          : std::string("\nstatus: complete\n"));
  close_checked(summary_txt, dir / output::kSummaryText);
  // The directory's files once summary.json is there too (checkpoints and snapshots included).
  std::vector<std::string> names{output::kSummaryJson};
  for (const auto& e : fs::directory_iterator(dir)) {
    std::error_code ec;  // a symbolic link that loops is no file of the run, not an error
    if (e.is_regular_file(ec) && e.path().filename() != output::kSummaryJson && e.path().filename() != output::kLock)
      names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  std::string files;
  for (const auto& n : names) files += (files.empty() ? "\"" : ", \"") + n + "\"";
  std::ofstream summary_json(dir / output::kSummaryJson);
  summary_json << json << ",\n  \"output_files\": [" << files << "]\n}\n";
  try {
    close_checked(summary_json, dir / output::kSummaryJson);
  } catch (const IoError&) {
    std::error_code ec;
    fs::remove(dir / output::kSummaryText, ec);  // its status line must not stand for a run that ended in an error
    throw;
  }
}

}  // namespace rondel
