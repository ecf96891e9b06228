// The discs of a new scene (Simulation's set-up, Simulation.cpp): built whole on every rank or, for a lattice, each
// rank those of its cells or its block, and for a Rondel file its block (scene::in_blocks); measured over the ranks;
// glued to rough walls; sent to the owners of their cells; and checked for initial overlaps on the first neighbour
// list, the same message on any rank count.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>

#include "app/BondList.hpp"
#include "app/Restart.hpp"
#include "app/RowGeometry.hpp"
#include "app/Simulation.hpp"
#include "app/StartChecks.hpp"
#include "core/Errors.hpp"
#include "core/ExactSum.hpp"
#include "core/Format.hpp"
#include "core/SceneBuilder.hpp"
#include "parallel/Agreement.hpp"
#include "parallel/StateFile.hpp"

namespace rondel {

namespace fs = std::filesystem;

void Simulation::build_discs() {
  agree(comm_, [&] { add_scene_discs(); });
  measure_radii();    // every rank holds the whole scene here, or its block of it (scene::in_blocks)
  if (n_discs_ == 0)  // over the ranks: a block may be empty (more ranks than discs)
    throw InputError(config_.scene.type->source != SceneType::Source::keys
                         ? "scene.file '" + config_.scene.file + "' holds no discs: the scene is empty"
                         : std::string("the scene has no discs (scene.type = ") + config_.scene.type->name + ")");
  if (boundaries_.rough()) {
    Boundaries::glue(discs_, walls_, config_.rough_depth > 0.0 ? config_.rough_depth : 2.0 * R_max_);
    assign_rough_materials();
  }
  warn_unused_materials();
  setup_neighbours();
}

namespace {

// A scene built whole on every rank of a run on several ranks draws a warning above this many discs.
constexpr std::size_t kWholeSceneWarning = 1'000'000;
// What such a set-up holds a disc of the whole scene on every rank (docs/scaling.md; tools/scaling_model.py).
constexpr double kWholeSceneBytes = 315.0;

// Puts a new scene's discs into the rank's store, each wrapped into the domain (refused outside it) and, in a moving
// cell, given the mean flow's velocity (cell.flow_start); room for the ghosts is reserved with them.
class StoreScene final : public SceneSink {
 public:
  StoreScene(const Config& config, DiscStore& discs, bool ghosts) : config_(config), discs_(discs), ghosts_(ghosts) {}
  void reserve(std::size_t n) override { discs_.reserve(n + (ghosts_ ? DiscExchange::ghost_room(n) : 0)); }
  void add(const SceneDisc& d) override {
    Vec2 x = d.x;
    config_.domain.wrap(x);
    if (!config_.domain.contains(x))
      throw InputError("disc " + std::to_string(d.gid) + " at (" + fmt(d.x.x) + ", " + fmt(d.x.y) +
                       ") lies outside the domain [" + fmt(config_.domain.xlo) + ", " + fmt(config_.domain.xhi) +
                       "] x [" + fmt(config_.domain.ylo) + ", " + fmt(config_.domain.yhi) + "] (from " +
                       start_checks::scene_keys(config_) + ")");
    const Vec2 v = config_.cell_flow_start && config_.domain.moving ? d.v + config_.domain.flow(x) : d.v;
    discs_.add(d.gid, d.material, d.radius, config_.materials[static_cast<std::size_t>(d.material)], x, v, d.omega);
  }

 private:
  const Config& config_;
  DiscStore& discs_;
  bool ghosts_;
};

}  // namespace

void Simulation::add_scene_discs() {
  const std::string dir = config_.source_file.empty() ? "" : fs::path(config_.source_file).parent_path().string();
  const FileScene files(config_, walls_, config_.domain, comm_);
  const SceneInputs in{config_.scene, config_.domain, dir, &files};
  StoreScene store(config_, discs_, comm_.size() > 1);
  if (const double radius = config_.cell_deforms() ? 0.0 : scene::by_cells(in); radius > 0.0) {
    // Each rank finds the discs of its cells: the decomposition first, on the range of the discs' largest radius
    // (the neighbour skin's default is a quarter of the mean radius), weighted by the discs each cell will hold; no
    // disc moves to its owner, and they go straight into the store.
    const SceneType& type = *config_.scene.type;
    const Partition::RectUnits units = [&](int x0, int y0, int x1, int y1) {
      return type.rect_count(in, decomposition_->grid(), x0, y0, x1, y1);
    };
    const double mean = type.mean_radius ? type.mean_radius(config_.scene) : radius;
    const double range = NeighbourList(skin_for(mean)).range(radius);
    start_checks::check_cells(config_, range);  // as setup_neighbours will: a grid this machine can hold
    make_decomposition(false, range, &units);
    type.cells(in, decomposition_->grid(), decomposition_->own_cells(), store);
  } else {
    const std::vector<SceneDisc> scene =
        config_.scene.type->block ? build_scene_block(in, comm_.rank(), comm_.size()) : build_scene(in);
    if (!scene::in_blocks(config_.scene) && comm_.size() > 1 && scene.size() > kWholeSceneWarning && comm_.root())
      std::cerr << "rondel: warning: scene.type = " << config_.scene.type->name << " builds all its " << scene.size()
                << " discs on every rank (" << fmt(static_cast<double>(scene.size()) * kWholeSceneBytes * 1e-9)
                << " GB each during the set-up)"
                << (config_.scene.type->draws_radii && !config_.scene.type->by_cells
                        ? "; scene.type = random_tiles places each rank's own"
                        : "")
                << " (docs/scaling.md, \"Set-up\")\n";
    store.reserve(scene.size());
    for (const auto& d : scene) store.add(d);
  }
  box0_ = Boundaries::box(walls_, config_.domain);  // a file scene may have moved the box walls
}

void Simulation::assign_rough_materials() {
  // walls.rough_materials: the discs glued to a box wall take that wall's material (mass and inertia too).
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) {
    if (!is_attached(discs_.flags[i])) continue;
    const int side = walls_[attached_wall(discs_.flags[i])].box_side;
    const int mat = side >= 0 ? config_.scene.rough_materials.at(static_cast<std::size_t>(side)) : -1;
    if (mat >= 0) discs_.set_material(i, mat, config_.materials[static_cast<std::size_t>(mat)]);
  }
}

void Simulation::warn_unused_materials() const {
  // A material that no disc (on any rank) and no wall has is most likely a typo.
  std::vector<bool> used(config_.materials.size(), false);
  for (std::size_t i = 0; i < discs_.n_owned(); ++i) used[static_cast<std::size_t>(discs_.material[i])] = true;
  for (const Wall& w : walls_) used[static_cast<std::size_t>(w.material)] = true;
  for (std::size_t m = 0; m < used.size(); ++m)
    if (!comm_.any(used[m]) && comm_.root())
      std::cerr << "rondel: warning: material '" << config_.materials[m].name << "' ([material."
                << config_.materials[m].name << "]) is used by no disc and no wall\n";
}

void Simulation::measure_radii() {
  double R_min = INFINITY, R_max = 0.0;
  ExactSum R_sum;
  for (std::size_t i = 0; i < discs_.n_owned(); ++i)
    R_min = std::min(R_min, discs_.radius[i]), R_max = std::max(R_max, discs_.radius[i]), R_sum += discs_.radius[i];
  R_min_ = -comm_.max(-R_min);
  R_max_ = comm_.max(R_max);
  R_total_ = comm_.exact_sum(R_sum);
  n_discs_ = comm_.sum(static_cast<std::int64_t>(discs_.n_owned()));
}

void Simulation::distribute_discs() {
  if (decomposition_) {  // built cell by cell (add_scene_discs) on the range its radius gave
    const CellGrid grid(config_.domain, neighbours_.range(R_max_), cell_sizing());
    if (grid.nx() == decomposition_->grid().nx() && grid.ny() == decomposition_->grid().ny())
      return weighed_ ? void() : settle_owners();
    return route_to_owners();  // a range that rounds to another grid: the discs go to the owners of this one
  }
  if (scene::in_blocks(config_.scene)) return route_to_owners();  // each rank built its block
  // Every rank built the whole scene; each keeps the discs of its cells.
  make_decomposition(true, neighbours_.range(R_max_));
  std::vector<bool> elsewhere(discs_.n_owned());
  for (std::size_t i = 0; i < discs_.n_owned(); ++i)
    elsewhere[i] = decomposition_->owner(discs_.position[i]) != comm_.rank();
  discs_.remove_owned(elsewhere);
}

void Simulation::route_to_owners() {
  // Discs (with their rows) go to the owners of an equal-cell cut (from any rank), then to the cut weighted by
  // their work.
  make_decomposition(false, neighbours_.range(R_max_));
  exchange_.migrate(discs_, pairs_, wall_rows_, *decomposition_, comm_, true, bond_rows());
  decomposition_->migrated();
  settle_owners();
}

void Simulation::settle_owners() {
  if (decomposition_->repartition(discs_, pairs_)) {
    exchange_.migrate(discs_, pairs_, wall_rows_, *decomposition_, comm_, false, bond_rows());
    decomposition_->migrated();
  }
}

void Simulation::create_bonds() {
  // The pair rows hold every pair within R1 + R2 + skin: a gap of bonds.gap x the smaller radius must lie within.
  agree(comm_, [&] {
    if (!(config_.bond_gap * R_max_ < neighbours_.skin()))
      throw InputError("bonds.gap = " + fmt(config_.bond_gap) + " of the largest radius (" + fmt(R_max_) +
                       " m) reaches beyond the neighbour skin (" + fmt(neighbours_.skin()) +
                       " m): lower bonds.gap or raise neighbour.skin above " + fmt(config_.bond_gap * R_max_) + " m");
    if (config_.bond_file.empty())
      bonds::create(discs_, config_.domain, config_.params, pairs_, config_.bond_gap, bonds_);
  });
  if (!config_.bond_file.empty()) bonds_from_file();
}

void Simulation::bonds_from_file() {
  // Each rank reads a block of the list; the pairs go to the owners of their discs (the restart's routing), which
  // find both discs (owned or ghosts) and check the pair; the line numbers ride in Fb_n until then.
  const std::string dir = config_.source_file.empty() ? "" : fs::path(config_.source_file).parent_path().string();
  const std::string path = scene::resolve(config_.bond_file, dir);
  ContactTable rows = ContactTable::bond_table();
  bond_list::read_block(path, rows, comm_);
  const std::int64_t listed = comm_.sum(static_cast<std::int64_t>(rows.size()));
  agree(comm_, [&] { route_rows_to_owners(rows, true, discs_, comm_); });
  const ContactTable routed = rows;  // the lines of the pairs that relink drops
  ContactKey lost{-1, -1};
  bonds::relink(discs_, rows, lost);
  bonds_ = std::move(rows);
  std::int64_t line = std::numeric_limits<std::int64_t>::max();
  std::string why;
  const auto consider = [&](double at, const std::string& what) {
    if (static_cast<std::int64_t>(at) < line) line = static_cast<std::int64_t>(at), why = what;
  };
  const auto pair_text = [](ContactKey k) { return "discs " + std::to_string(k.lo) + " and " + std::to_string(k.hi); };
  if (lost.lo >= 0) {
    const auto it = std::lower_bound(routed.key.begin(), routed.key.end(), lost);
    consider(routed.slot[0][static_cast<std::size_t>(it - routed.key.begin())],
             pair_text(lost) + ": one of them does not exist, or they are farther apart than the neighbour range");
  }
  for (std::size_t r = 0; r < bonds_.size(); ++r) {
    const auto i = static_cast<std::size_t>(bonds_.i1[r]), j = static_cast<std::size_t>(bonds_.i2[r]);
    const std::size_t a = static_cast<std::size_t>(discs_.material[i]),
                      b = static_cast<std::size_t>(discs_.material[j]);
    bonds_.param[r] = static_cast<std::int32_t>(config_.params.pair_index(a, b));
    const double R = std::min(discs_.radius[i], discs_.radius[j]);
    const double gap = RowGeometry::pair(discs_, config_.domain, i, j).u_n;  // -gap
    if (!(config_.params.pair(a, b).kb_n > 0.0))
      consider(bonds_.slot[0][r], pair_text(bonds_.key[r]) + " are of materials " + config_.materials[a].name +
                                      " and " + config_.materials[b].name + ", a pair that [bonds] does not bond");
    else if (-gap > config_.bond_gap * R)
      consider(bonds_.slot[0][r], pair_text(bonds_.key[r]) + " are " + fmt(-gap / R) +
                                      " of the smaller radius apart, above bonds.gap = " + fmt(config_.bond_gap));
    bonds_.slot[0][r] = 0.0;
  }
  const std::int64_t first = -comm_.max(-line);
  const std::int64_t kept = comm_.sum(bonds::booked(discs_, bonds_));
  agree(comm_, [&] {
    if (first != std::numeric_limits<std::int64_t>::max() && line == first)
      throw InputError("bonds.file '" + path + "' line " + std::to_string(first) + ": " + why);
    if (first == std::numeric_limits<std::int64_t>::max() && kept != listed)
      throw InputError("bonds.file '" + path + "' lists " + std::to_string(listed) + " pairs but " +
                       std::to_string(kept) + " distinct pairs of existing discs: a pair is listed twice, or names " +
                       "discs that do not exist");
  });
}

void Simulation::check_initial_overlaps() {
  // On the first neighbour list (its rows join this rank's discs and their ghosts): each pair counted by the rank
  // that owns its lower gid and each wall contact by the disc's owner; the count summed, the worst taken over the
  // ranks (ties: the lowest key), so that the message is the same on any rank count. Collective and agreed.
  const ContactTable& pairs = pairs_;
  const ContactTable& walls = wall_rows_;
  std::int64_t count = 0;
  double worst = 0.0;
  ContactKey worst_key{-1, -1};
  bool worst_wall = false;
  auto consider = [&](double u_n, double R, ContactKey key, bool wall) {
    const double ratio = u_n / R;
    if (ratio <= config_.scene.max_initial_overlap) return;
    ++count;
    if (ratio > worst || (ratio == worst && (wall < worst_wall || (wall == worst_wall && key < worst_key))))
      worst = ratio, worst_key = key, worst_wall = wall;
  };
  const std::size_t owned = discs_.n_owned();
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    const auto i = static_cast<std::size_t>(pairs.i1[r]), j = static_cast<std::size_t>(pairs.i2[r]);
    const std::size_t lower = discs_.gid[i] < discs_.gid[j] ? i : j;
    if (lower >= owned) continue;
    consider(RowGeometry::pair(discs_, config_.domain, i, j).u_n, std::min(discs_.radius[i], discs_.radius[j]),
             pairs.key[r], false);
  }
  for (std::size_t r = 0; r < walls.size(); ++r) {
    const auto i = static_cast<std::size_t>(walls.i1[r]);
    if (i >= owned) continue;
    consider(RowGeometry::wall(discs_, walls_[walls.i2[r]], i).u_n, discs_.radius[i], walls.key[r], true);
  }
  count = comm_.sum(count);
  if (count == 0) return;
  const double global = comm_.max(worst);
  // The lowest key among the ranks' worst of that ratio: pairs before wall contacts, then by key.
  const bool mine = worst == global;
  const std::int64_t wall = -comm_.max(mine ? -static_cast<std::int64_t>(worst_wall) : -2);
  const bool candidate = mine && static_cast<std::int64_t>(worst_wall) == wall;
  const std::int64_t lo = -comm_.max(candidate ? -worst_key.lo : std::numeric_limits<std::int64_t>::min());
  const std::int64_t hi =
      -comm_.max(candidate && worst_key.lo == lo ? -worst_key.hi : std::numeric_limits<std::int64_t>::min());
  const std::string where = wall != 0 ? "disc " + std::to_string(lo) + " and wall " + std::to_string(hi)
                                      : "discs " + std::to_string(lo) + " and " + std::to_string(hi);
  agree(comm_, [&] {
    throw InputError(std::to_string(count) + " initial overlaps exceed scene.max_initial_overlap = " +
                     fmt(config_.scene.max_initial_overlap) + " of the smaller radius; the worst is " + fmt(global) +
                     " between " + where + " (from " + start_checks::scene_keys(config_) + ")");
  });
}

}  // namespace rondel
