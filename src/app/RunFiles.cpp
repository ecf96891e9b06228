// The output directory of a run and its files (docs/design.md section 7, FORMAT.md).
#include "app/RunFiles.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>

#include "core/Errors.hpp"

namespace rondel {

namespace fs = std::filesystem;

void RunFiles::prepare(bool resuming, std::int64_t step) {
  const fs::path dir(config_.output);
  bool exists = false, writable = true;
  if (comm_.root()) {
    exists = fs::exists(dir) && !(fs::is_directory(dir) && fs::is_empty(dir));
    if (!exists || config_.overwrite || resuming) {
      std::error_code ec;
      fs::create_directories(dir, ec);
      writable = std::ofstream(dir / "config.ini").good();
    }
  }
  if (comm_.any(exists) && !config_.overwrite && !resuming)
    throw ConfigError("run.output = '" + config_.output +
                      "' already exists and is not empty; choose another directory or set run.overwrite = true");
  if (comm_.any(!writable))
    throw ConfigError("run.output = '" + config_.output + "' cannot be written (permissions, or a file of that name)");
  checkpoints_ = std::make_unique<Checkpointing>(config_.output, config_.checkpoint_keep, config_.snapshot_fields,
                                                 config_.domain, comm_);
  if (resuming)
    checkpoints_->adopt_snapshots(step);
  else
    checkpoints_->remove_old_files();
  comm_.barrier();
  if (!comm_.root()) return;
  std::error_code ec;
  for (const char* stale : {"final.csv", "summary.txt", "summary.json"}) fs::remove(dir / stale, ec);
  std::ofstream(dir / "config.ini") << "# resolved configuration of this run (every key, defaults included)\n"
                                    << config_.resolved_text;
  log_.open(dir / "log.txt", resuming ? std::ios::app : std::ios::trunc);
  diag_.open((dir / "diagnostics.csv").string(), resuming);
  const bool measures_existed = resuming && fs::exists(dir / "measures.csv");
  measures_.open(dir / "measures.csv", resuming ? std::ios::app : std::ios::trunc);
  if (!measures_existed) measures_ << MeasuresRow::header() << '\n';
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
  if (comm_.root() && log_.is_open()) log_ << line << '\n' << std::flush;
}

void RunFiles::write_diagnostics(const DiagnosticsRow& row) {
  if (comm_.root()) diag_.write(row);
}

void RunFiles::write_measures(const MeasuresRow& row) {
  if (comm_.root()) measures_ << row.csv() << '\n';
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

void RunFiles::write_results(const std::string& final_state, const std::string& summary, const std::string& json,
                             bool stopped) const {
  if (!comm_.root()) return;
  const fs::path dir(config_.output);
  std::ofstream(dir / "final.csv") << final_state;
  std::ofstream(dir / "summary.txt") << summary
                                     << (stopped ? "\nstatus: stopped by a signal; resume with --resume " +
                                                       config_.output + "\n"
                                                 : std::string("\nstatus: complete\n"));
  // The directory's files once summary.json is there too (checkpoints and snapshots included).
  std::vector<std::string> names{"summary.json"};
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && e.path().filename() != "summary.json") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  std::string files;
  for (const auto& n : names) files += (files.empty() ? "\"" : ", \"") + n + "\"";
  std::ofstream(dir / "summary.json") << json << ",\n  \"output_files\": [" << files << "]\n}\n";
}

}  // namespace rondel
