#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "app/Checkpointing.hpp"
#include "app/Measures.hpp"
#include "core/Config.hpp"
#include "core/Diagnostics.hpp"
#include "parallel/Communicator.hpp"

namespace rondel {

// The output directory of a run (run.output) and its files: config.ini, log.txt, diagnostics.csv,
// measures.csv, the checkpoints and snapshots (through Checkpointing), final.csv, summary.txt and
// summary.json.
// Without files (write_files = false) only log() remains, and it prints nothing.
class RunFiles {
 public:
  RunFiles(const Config& config, const Communicator& comm, bool write_files)
      : config_(config), comm_(comm), write_files_(write_files) {}

  RunFiles(const RunFiles&) = delete;
  RunFiles& operator=(const RunFiles&) = delete;
  // Rank 0: gives the directory's lock back (removes rondel.lock), whatever ended the run.
  ~RunFiles();

  // Collective: checks that run.output may be used (empty, run.overwrite, or the directory of the run being
  // resumed), creates it, takes its lock (rondel.lock: no second run, nor the orphaned ranks of a killed one,
  // writes into it meanwhile) and opens its files. A run resumed from `checkpoint` at `step` keeps the rows
  // of diagnostics.csv and measures.csv up to `step` and the snapshots up to it, and appends: the directory
  // is then what an uninterrupted run leaves. Errors found by rank 0 alone are agreed (every rank throws
  // them). Rank 0's row writers below throw IoError when a file cannot be written: call them inside an
  // agreement (parallel/Agreement.hpp).
  void prepare(const std::string& checkpoint, std::int64_t step);
  // Collective: a new run's id, 128 random bits in hexadecimal drawn on rank 0 (metadata: never an input of
  // the physics), the same on every rank.
  static std::string new_run_id(const Communicator& comm);
  // True once prepare() has opened an output directory.
  bool has_directory() const { return checkpoints_ != nullptr; }
  // Rank 0: to the terminal (when the run writes files) and to log.txt.
  void log(const std::string& line);
  // Rank 0: to log.txt only (what the terminal need not see: the resolved configuration).
  void log_file_only(const std::string& line);
  // The progress line that log() erases before it prints (nullptr: none).
  void set_progress(ProgressLine* progress) { progress_ = progress; }
  // Rank 0: one row of diagnostics.csv, of measures.csv.
  void write_diagnostics(const DiagnosticsRow& row);
  void write_measures(const MeasuresRow& row);
  // Collective: a checkpoint of `header` and the state; logs and returns its path.
  std::string write_checkpoint(const StateHeader& header, DiscStore& discs, const ContactTable& pairs,
                               const ContactTable& wall_rows, const WallSet& walls, const StateExtras& extras = {});
  void write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls, std::int64_t n_discs,
                      const StateExtras& extras = {});
  // Wall time of the run so far, recorded in the checkpoints' metadata.
  void add_wall_seconds(double s) { wall_seconds_ += s; }
  // Rank 0: the rows of diagnostics.csv and measures.csv reach their files (checked).
  void flush_tables();
  // Where final.csv goes (written by every rank, in gid order: Simulation::write_final).
  std::string final_path() const;
  // Rank 0: summary.txt (the summary text, then the status line) and summary.json (`json`, a JSON object
  // without its closing brace; the list of the directory's files is appended).
  void write_results(const std::string& summary, const std::string& json, bool stopped);
  // Rank 0: throws IoError when a line of log.txt could not be written since the start (log() itself never
  // throws: it is called between collectives). Call inside an agreement.
  void check_log();

 private:
  // Rank 0: the directory may be used (ConfigError otherwise), exists and is locked by this run.
  void claim_directory(const std::string& checkpoint);
  void take_lock(const std::filesystem::path& dir);
  // Rank 0: config.ini written, log.txt, diagnostics.csv and measures.csv opened (a resumed run's tables
  // cut back to `step` first).
  void open_files(bool resuming, std::int64_t step);
  static std::string write_failure(const std::filesystem::path& path);
  [[noreturn]] static void write_failed(const std::filesystem::path& path);
  static void check_stream(const std::ostream& out, const std::filesystem::path& path);
  static void close_checked(std::ofstream& out, const std::filesystem::path& path);

  const Config& config_;
  const Communicator& comm_;
  bool write_files_;
  std::unique_ptr<Checkpointing> checkpoints_;
  std::filesystem::path lock_;  // rank 0: the lock file this run holds (empty: none)
  ProgressLine* progress_ = nullptr;
  double wall_seconds_ = 0.0;
  std::string log_failed_;  // the first failure to write log.txt (check_log)  // wall time of earlier runs of this
                            // simulation (before a restart) and this one
  std::ofstream log_, measures_;
  DiagnosticsWriter diag_;
};

}  // namespace rondel
