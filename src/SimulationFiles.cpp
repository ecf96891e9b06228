// The file side of Simulation: the output directory, checkpoints, snapshots, restarts and scenes read from
// a Rondel file (DESIGN.md section 7, FORMAT.md).
#include <filesystem>

#include "Simulation.hpp"
#include "core/Errors.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {

namespace fs = std::filesystem;

void Simulation::prepare_output(bool resuming) {
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
  files_ = std::make_unique<Checkpointing>(config_.output, config_.checkpoint_keep, config_.snapshot_fields, comm_);
  if (resuming) files_->adopt_snapshots(step_);
  else files_->remove_old_files();
  comm_.barrier();
  if (!comm_.root()) return;
  std::error_code ec;
  for (const char* stale : {"final.csv", "summary.txt"}) fs::remove(dir / stale, ec);
  std::ofstream(dir / "config.ini") << "# resolved configuration of this run (every key, defaults included)\n"
                                    << config_.resolved_text;
  log_.open(dir / "log.txt", resuming ? std::ios::app : std::ios::trunc);
  diag_.open((dir / "diagnostics.csv").string(), resuming);
  const bool measures_existed = resuming && fs::exists(dir / "measures.csv");
  measures_.open(dir / "measures.csv", resuming ? std::ios::app : std::ios::trunc);
  if (!measures_existed) measures_ << MeasuresRow::header() << '\n';
}

StateHeader Simulation::state_header(const char* kind) const {
  StateHeader h;
  h.kind = kind;
  h.step = step_;
  h.time = time_;
  h.dt = dt_;
  h.normal_law = config_.normal_law;
  h.tangential_law = config_.tangential_law;
  h.rolling_law = config_.rolling_law;
  h.slots = history_slots(laws_);
  h.config = config_.resolved_text;
  h.box_width0 = box0_.width;
  h.box_height0 = box0_.height;
  h.ledger = global_ledger();
  return h;
}

std::string Simulation::write_checkpoint() {
  if (!files_) throw ConfigError("a checkpoint needs an output directory (this simulation writes no files)");
  const std::string path =
      files_->write_checkpoint(state_header("checkpoint"), discs_, pairs_, wall_rows_, walls_, wall_seconds_);
  log("checkpoint at step " + std::to_string(step_) + ": " + path);
  return path;
}

void Simulation::write_snapshot() {
  const auto n = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
  files_->write_snapshot(state_header("snapshot"), discs_, walls_, n);
}

std::vector<SceneDisc> Simulation::scene_from_file() {
  // Every rank reads every disc (the scene is then distributed like any other). A directory means its
  // newest complete checkpoint. Box walls take their positions from the file (a prepared sample keeps its
  // box); contact history starts afresh, and step, time and strains start at zero: a new test stage.
  const Communicator self = Communicator::self();
  std::string path = config_.scene.file;
  if (fs::is_directory(path)) path = Checkpointing::newest_checkpoint(path, self);
  read_state_header(path, self);
  DiscStore d;
  read_state_discs(path, d, self);
  const WallSet walls = read_state_walls(path, self);
  if (walls.size() == walls_.size())
    for (std::size_t w = 0; w < walls.size(); ++w) walls_[w].p0 = walls[w].p0, walls_[w].p1 = walls[w].p1;
  box0_ = Boundaries::box(walls_, config_.domain);
  std::vector<SceneDisc> out;
  for (std::size_t i = 0; i < d.n_owned(); ++i)
    out.push_back({d.gid[i], d.position[i], d.radius[i], d.velocity[i], d.omega[i]});
  return out;
}

void Simulation::check_laws_match(const StateHeader& h, const std::string& path) const {
  const auto slots = history_slots(laws_);
  if (h.normal_law == config_.normal_law && h.tangential_law == config_.tangential_law &&
      h.rolling_law == config_.rolling_law && h.slots == slots)
    return;
  if (config_.reset_history) return;
  auto list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
    return s.empty() ? std::string("none") : s;
  };
  throw InputError("'" + path + "' was written with laws normal " + h.normal_law + ", tangential " +
                   h.tangential_law + ", rolling " + h.rolling_law + " (history slots " + list(h.slots) +
                   ") but the configuration selects " + config_.normal_law + ", " + config_.tangential_law + ", " +
                   config_.rolling_law + " (" + list(slots) +
                   "): select the same laws, or set run.reset_history = true to start without its contact history");
}

void Simulation::load_checkpoint(const std::string& path) {
  const StateHeader h = read_state_header(path, comm_);
  check_laws_match(h, path);
  read_state_discs(path, discs_, comm_);
  if (comm_.sum(static_cast<std::int64_t>(discs_.n_owned())) == 0) throw InputError("'" + path + "' holds no discs");
  const WallSet walls = read_state_walls(path, comm_);
  if (walls.size() != walls_.size())
    throw InputError("'" + path + "' has " + std::to_string(walls.size()) + " walls but the configuration defines " +
                     std::to_string(walls_.size()));
  for (std::size_t w = 0; w < walls.size(); ++w) {  // positions and loads from the file, controls from the config
    walls_[w].p0 = walls[w].p0;
    walls_[w].p1 = walls[w].p1;
    walls_[w].velocity = walls[w].velocity;
    walls_[w].force = walls[w].force;
    walls_[w].normal_force = walls[w].normal_force;
    walls_[w].contacts = walls[w].contacts;
  }
  box0_.width = h.box_width0;
  box0_.height = h.box_height0;
  setup_neighbours();
  resolve_time_step();
  dt_ = h.dt;
  step_ = h.step;
  time_ = h.time;
  make_decomposition(false);
  ContactTable no_pairs = make_contact_table(laws_), no_walls = make_contact_table(laws_);
  exchange_.migrate(discs_, no_pairs, no_walls, *decomposition_, comm_);
  const bool same_laws = h.slots == history_slots(laws_) && h.rolling_law == config_.rolling_law &&
                         h.tangential_law == config_.tangential_law;
  if (same_laws) {
    read_state_rows(path, pairs_, wall_rows_, comm_);
    route_rows_to_owners(pairs_, true, discs_, comm_);
    route_rows_to_owners(wall_rows_, false, discs_, comm_);
  }
  // The ledger continues: every rank carries the global terms (KE0, the scale), rank 0 the ranks' shares.
  LedgerTerms::visit_terms(
      [this](const LedgerTermInfo& t, double& mine, const double& saved) {
        if (!(t.uses & kTermRankShare) || comm_.root()) mine = saved;
      },
      ledger_, h.ledger);
}

}  // namespace rondel
