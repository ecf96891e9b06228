#pragma once
#include <cstdint>
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

  // Collective: checks that run.output may be used (empty, run.overwrite, or a resumed run), creates it and
  // opens its files; a resumed run at `step` appends and keeps its snapshots.
  void prepare(bool resuming, std::int64_t step);
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
                               const ContactTable& wall_rows, const WallSet& walls);
  void write_snapshot(const StateHeader& header, DiscStore& discs, const WallSet& walls, std::int64_t n_discs);
  // Wall time of the run so far, recorded in the checkpoints' metadata.
  void add_wall_seconds(double s) { wall_seconds_ += s; }
  // Rank 0: final.csv, summary.txt (the summary text, then the status line) and summary.json (`json`, a
  // JSON object without its closing brace: the list of the directory's files is added here).
  void write_results(const std::string& final_state, const std::string& summary, const std::string& json,
                     bool stopped) const;

 private:
  const Config& config_;
  const Communicator& comm_;
  bool write_files_;
  std::unique_ptr<Checkpointing> checkpoints_;
  ProgressLine* progress_ = nullptr;
  double wall_seconds_ = 0.0;  // wall time of earlier runs of this simulation (before a restart) and this one
  std::ofstream log_, measures_;
  DiagnosticsWriter diag_;
};

}  // namespace rondel
