// The output directory of a run and its files (docs/design.md section 7, FORMAT.md).
#include "app/RunFiles.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "core/Errors.hpp"
#include "parallel/Agreement.hpp"

namespace rondel {

namespace fs = std::filesystem;

void RunFiles::prepare(bool resuming, std::int64_t step) {
  // Rank 0 looks at the directory and creates it; every step that only rank 0 does is agreed, so that its
  // error (a directory in use, a file it cannot write) stops every rank.
  agree(comm_, [&] { claim_directory(resuming); });
  checkpoints_ = std::make_unique<Checkpointing>(config_.output, config_.checkpoint_keep, config_.snapshot_fields,
                                                 config_.domain, comm_);
  if (resuming)
    agree(comm_, [&] { checkpoints_->adopt_snapshots(step); });
  else
    agree(comm_, [&] { checkpoints_->remove_old_files(); });
  agree(comm_, [&] { open_files(resuming); });
}

void RunFiles::claim_directory(bool resuming) const {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  const bool exists = fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir));
  if (exists && !config_.overwrite && !resuming)
    throw ConfigError("run.output = '" + config_.output +
                      "' already exists and is not empty; choose another directory or set run.overwrite = true");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!std::ofstream(dir / "config.ini").good())
    throw ConfigError("run.output = '" + config_.output + "' cannot be written (permissions, or a file of that name)");
}

void RunFiles::open_files(bool resuming) {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  std::error_code ec;
  for (const char* stale : {"final.csv", "summary.txt", "summary.json"}) fs::remove(dir / stale, ec);
  std::ofstream config(dir / "config.ini");
  config << "# resolved configuration of this run (every key, defaults included)\n" << config_.resolved_text;
  close_checked(config, dir / "config.ini");
  log_.open(dir / "log.txt", resuming ? std::ios::app : std::ios::trunc);
  check_stream(log_, dir / "log.txt");
  diag_.open((dir / "diagnostics.csv").string(), resuming);
  const bool measures_existed = resuming && fs::exists(dir / "measures.csv");
  measures_.open(dir / "measures.csv", resuming ? std::ios::app : std::ios::trunc);
  if (!measures_existed) measures_ << MeasuresRow::header() << '\n';
  check_stream(measures_, dir / "measures.csv");
}

std::string RunFiles::write_failure(const fs::path& path) {
  return "cannot write '" + path.string() + "' (disk full, permissions, or a removed directory)";
}

void RunFiles::write_failed(const fs::path& path) { throw IoError(write_failure(path)); }

void RunFiles::check_stream(const std::ostream& out, const fs::path& path) {
  if (!out.good()) write_failed(path);
}

void RunFiles::close_checked(std::ofstream& out, const fs::path& path) {
  out.flush();
  check_stream(out, path);
  out.close();
  if (out.fail()) throw IoError("cannot close '" + path.string() + "' (disk full?)");
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
  if (!log_.good() && log_failed_.empty()) log_failed_ = write_failure(fs::path(config_.output) / "log.txt");
}

void RunFiles::write_diagnostics(const DiagnosticsRow& row) {
  if (!comm_.root()) return;
  diag_.write(row);
  if (!diag_.good()) write_failed(fs::path(config_.output) / "diagnostics.csv");
}

void RunFiles::write_measures(const MeasuresRow& row) {
  if (!comm_.root() || !measures_.is_open()) return;
  measures_ << row.csv() << '\n';
  check_stream(measures_, fs::path(config_.output) / "measures.csv");
}

std::string RunFiles::write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                                       const ContactTable& wall_rows, const WallSet& walls) {
  const std::string path = checkpoints_->write_checkpoint(header, discs, pairs, wall_rows, walls, wall_seconds_);
  log("checkpoint at step " + std::to_string(header.step) + ": " + path);
  return path;
}

void RunFiles::write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls, std::int64_t n_discs) {
  checkpoints_->write_snapshot(header, discs, walls, n_discs);
}

void RunFiles::flush_tables() {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  // The rows of diagnostics.csv and measures.csv reach their files (the writers flush them once a second).
  if (!diag_.flush()) write_failed(dir / "diagnostics.csv");
  if (measures_.is_open()) check_stream(measures_.flush(), dir / "measures.csv");
}

std::string RunFiles::final_path() const { return (fs::path(config_.output) / "final.csv").string(); }

void RunFiles::write_results(const std::string& summary, const std::string& json, bool stopped) {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  std::ofstream summary_txt(dir / "summary.txt");
  summary_txt << summary
              << (stopped ? "\nstatus: stopped by a signal; resume with --resume " + config_.output + "\n"
                          : std::string("\nstatus: complete\n"));
  close_checked(summary_txt, dir / "summary.txt");
  // The directory's files once summary.json is there too (checkpoints and snapshots included).
  std::vector<std::string> names{"summary.json"};
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "summary.json") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string files;
  for (const auto& n : names) files += (files.empty() ? "\"" : ", \"") + n + "\"";
  std::ofstream summary_json(dir / "summary.json");
  summary_json << json << ",\n  \"output_files\": [" << files << "]\n}\n";
  close_checked(summary_json, dir / "summary.json");
}

}  // namespace rondel
