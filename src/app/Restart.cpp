// A run's state in a Rondel file, both ways (docs/design.md section 7, FORMAT.md): the header written with a
// checkpoint or snapshot, and a restart or a scene taken back from one.
#include "app/Restart.hpp"

#include <filesystem>

#include "app/Checkpointing.hpp"
#include "app/Reports.hpp"
#include "core/Errors.hpp"
#include "core/WallKinds.hpp"

namespace rondel {

namespace fs = std::filesystem;

namespace {

// A file's material table must be the configuration's (a file written before the materials existed has none:
// then the configuration must have one material), unless run.accept_materials.
void check_material_table(const std::string& path, const StateHeader& h, const Config& config) {
  const std::string mine = material_table_text(config.materials);
  if (h.materials.empty() ? config.materials.size() == 1 : h.materials == mine) return;
  if (config.accept_materials) return;
  throw InputError("'" + path + "' was written with the material table\n" +
                   (h.materials.empty() ? std::string("(one material, no table)\n") : h.materials) +
                   "but the configuration has\n" + mine +
                   "(name, body, density, thickness, E, nu): use the same [material] sections, or set "
                   "run.accept_materials = true to take the configuration's materials by index");
}

// Every disc's material index names a material of the configuration.
void check_disc_materials(const std::string& path, const DiscStore& d, const Config& config) {
  for (std::size_t i = 0; i < d.n_owned(); ++i)
    if (d.material[i] < 0 || static_cast<std::size_t>(d.material[i]) >= config.materials.size())
      throw InputError("'" + path + "': disc " + std::to_string(d.gid[i]) + " has material " +
                       std::to_string(d.material[i]) + " but the configuration defines " +
                       std::to_string(config.materials.size()) + " materials (/discs/material)");
}

}  // namespace

StateHeader Restart::header(const RunState& state, const char* kind) {
  const Config& config = state.config;
  StateHeader h;
  h.kind = kind;
  h.step = state.step;
  h.time = state.time;
  h.dt = state.dt;
  h.normal_law = config.normal_law;
  h.tangential_law = config.tangential_law;
  h.rolling_law = config.rolling_law;
  h.slots = history_slots(state.laws);
  h.config = config.resolved_text;
  h.materials = material_table_text(config.materials);
  h.run_id = config.run_id;
  h.box_width0 = state.box0.width;
  h.box_height0 = state.box0.height;
  h.cell = config.domain;
  h.has_cell = true;
  h.flips = state.flips;
  h.ledger = Reports(state).global_ledger();
  return h;
}

std::vector<SceneDisc> Restart::scene_from_file(const std::string& file, const Config& config, WallSet& walls_out,
                                                Domain& cell, const Communicator& comm) {
  // Each rank reads its block of the discs (then sent to their owners, as a restart's); every rank reads the
  // header and the walls. A directory means its newest complete checkpoint. Box walls take their positions from the
  // file (a prepared sample keeps its box), a periodic cell its shape; contact history starts afresh, and step, time
  // and strains start at zero: a new test stage.
  const Communicator self = Communicator::self();
  std::string path = file;
  if (fs::is_directory(path)) path = Checkpointing::newest_checkpoint(path, self);
  const StateHeader header = read_state_header(path, self);
  check_material_table(path, header, config);
  const bool recorded = records_cell(header, cell);
  cell = recorded_cell(header, cell);
  DiscStore d;
  read_state_discs(path, d, comm);  // collective: this rank's block, the ids checked unique over the file
  check_disc_materials(path, d, config);
  const WallSet walls = read_state_walls(path, self);
  if (walls.size() == walls_out.size())
    for (std::size_t w = 0; w < walls.size(); ++w) {
      walls_out[w].p0 = walls[w].p0, walls_out[w].p1 = walls[w].p1;
      if (walls_out[w].rotates() && walls[w].kind == walls_out[w].kind) walls_out[w].normal = walls[w].normal;
    }
  // With cell.flow_start the discs start with their velocity apart from the file's own mean flow (its cell's
  // rates at that step), to which the new run adds its own: a stage at another rate starts from the state's
  // agitation, not from the old flow (whose mismatch would meet the boundary as a jump of the rate times L_y).
  const bool relative = config.cell_flow_start && recorded;
  std::vector<SceneDisc> out;
  for (std::size_t i = 0; i < d.n_owned(); ++i) {
    const Vec2 v = relative ? d.velocity[i] - header.cell.flow(d.position[i]) : d.velocity[i];
    out.push_back({d.gid[i], d.position[i], d.radius[i], v, d.omega[i], d.material[i]});
  }
  return out;
}

Restart::Restart(std::string path, const Config& config, const LawSelection& laws, const Communicator& comm)
    : path_(std::move(path)), config_(config), laws_(laws), comm_(comm), header_(read_state_header(path_, comm_)) {
  check_laws_match();
  check_material_table(path_, header_, config_);
}

void Restart::check_laws_match() const {
  const StateHeader& h = header_;
  const std::string& path = path_;
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
  throw InputError("'" + path + "' was written with laws normal " + h.normal_law + ", tangential " + h.tangential_law +
                   ", rolling " + h.rolling_law + " (history slots " + list(h.slots) +
                   ") but the configuration selects " + config_.normal_law + ", " + config_.tangential_law + ", " +
                   config_.rolling_law + " (" + list(slots) +
                   "): select the same laws, or set run.reset_history = true to start without its contact history");
}

bool Restart::same_laws() const {
  const StateHeader& h = header_;
  return h.slots == history_slots(laws_) && h.rolling_law == config_.rolling_law &&
         h.tangential_law == config_.tangential_law;
}

void Restart::read_discs(DiscStore& discs) const {
  read_state_discs(path_, discs, comm_);
  if (comm_.sum(static_cast<std::int64_t>(discs.n_owned())) == 0) throw InputError("'" + path_ + "' holds no discs");
  check_disc_materials(path_, discs, config_);
  // Accepted materials that differ: mass and inertia from the configuration's table, by index.
  if (config_.accept_materials && header_.materials != material_table_text(config_.materials))
    for (std::size_t i = 0; i < discs.n_owned(); ++i)
      discs.set_material(i, discs.material[i], config_.materials[static_cast<std::size_t>(discs.material[i])]);
}

void Restart::read_walls(WallSet& into) const {
  const WallSet walls = read_state_walls(path_, comm_);
  if (walls.size() != into.size())
    throw InputError("'" + path_ + "' has " + std::to_string(walls.size()) + " walls but the configuration defines " +
                     std::to_string(into.size()));
  for (std::size_t w = 0; w < walls.size(); ++w) {  // positions and loads from the file, controls from the config
    if (walls[w].kind != into[w].kind)
      throw InputError("'" + path_ + "': wall " + std::to_string(w) + " is a " + WallKinds::name(walls[w].kind) +
                       " in the file but a " + WallKinds::name(into[w].kind) + " in the configuration");
    into[w].p0 = walls[w].p0;
    into[w].p1 = walls[w].p1;
    if (into[w].rotates()) into[w].normal = walls[w].normal;  // a rotating line has turned its normal
    into[w].angle = walls[w].angle;
    into[w].velocity = walls[w].velocity;
    into[w].force = walls[w].force;
    into[w].normal_force = walls[w].normal_force;
    into[w].contacts = walls[w].contacts;
  }
}

void Restart::read_rows(ContactTable& pairs, ContactTable& wall_rows, const DiscStore& discs,
                        ContactTable* bonds) const {
  if (!same_laws()) return;
  read_state_rows(path_, pairs, wall_rows, comm_, bonds);
  route_rows_to_owners(pairs, true, discs, comm_);
  route_rows_to_owners(wall_rows, false, discs, comm_);
  if (bonds) route_rows_to_owners(*bonds, true, discs, comm_);
}

void Restart::read_ledger(EnergyLedger& ledger) const {
  // The ledger continues: every rank carries the global terms (KE0, the scale), rank 0 the ranks' shares.
  LedgerTerms::visit_terms(
      [this](const LedgerTermInfo& t, double& mine, const double& saved) {
        if (!(t.uses & kTermRankShare) || comm_.root()) mine = saved;
      },
      ledger, header_.ledger);
}

}  // namespace rondel
