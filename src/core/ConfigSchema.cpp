#include "core/ConfigSchema.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "core/ConfigRead.hpp"
#include "core/DiscStore.hpp"
#include "core/Partitioners.hpp"
#include "core/SceneTypes.hpp"
#include "core/Wall.hpp"
#include "core/WallKinds.hpp"

namespace rondel {

namespace po = boost::program_options;

namespace {

using config::at;
using config::Choice;
using config::kFinite;
using config::kGravity;
using config::kSpeed;
using Keys = config::KeyTable<Config>;
using Readers = std::vector<config::KeyReader<Config>>;

// Ranges used by several keys below.
constexpr Range kCount{0.0, INFINITY, false, true};       // an integer >= 0
constexpr Range kAtLeastOne{1.0, INFINITY, false, true};  // an integer >= 1
constexpr Range kFraction{0.0, 1.0, true, false};         // in (0, 1]
constexpr Range kOpenUnit{0.0, 1.0, true, true};          // in (0, 1)
// run.steps: t = step x dt keeps every step's increment (below 2^52 steps); more would run for years.
constexpr Range kSteps{0.0, 1e15, false, false};
using I64 = std::int64_t;

constexpr Choice<FinalFormat> kFinalFormats[] = {
    {"hex", FinalFormat::hex, "C99 %a, bit-exact"},
    {"decimal", FinalFormat::decimal, "%.17g, reads back to the same bits"}};
constexpr Choice<Distribution> kDistributions[] = {{"uniform_radius", Distribution::uniform_radius},
                                                   {"uniform_area", Distribution::uniform_area},
                                                   {"list", Distribution::list, "scene.sizes with scene.fractions"}};
constexpr Choice<Numbering> kNumberings[] = {
    {"placement", Numbering::placement, "the order they are placed, largest first"},
    {"rows", Numbering::rows, "in rows across the region, by x: faster beyond ~100,000 discs"}};
constexpr Choice<MaterialBy> kMaterialBy[] = {{"number", MaterialBy::number}, {"area", MaterialBy::area}};

// The words of scene.type: the rows of the scene registry.
std::span<const Choice<const SceneType*>> scene_type_choices() {
  static const std::vector<Choice<const SceneType*>> list = [] {
    std::vector<Choice<const SceneType*>> out;
    for (const SceneType* t : scene_types()) out.push_back({t->name, t, t->help});
    return out;
  }();
  return list;
}

std::vector<std::string> box_side_words() { return {std::begin(kBoxSides), std::end(kBoxSides)}; }

// The key lists below keep one key per line (clang-format would run them together).
void add_run_sections(po::options_description& all, std::vector<KeySpec>& keys, Readers* readers) {
  po::options_description run("[run]"), out("[output] snapshots and checkpoints (HDF5, FORMAT.md)"),
      diag("[diagnostics]");
  // clang-format off
  Keys(run, keys, readers)
      .number("run.steps", at(&Config::steps), I64{1000}, "-", kSteps, "number of time steps")
      .number("run.dt", at(&Config::dt), 0.0, "s", kNonNegative, "time step; 0 = safety x critical step")
      .number("run.safety", at(&Config::safety), 0.2, "-", kFraction, "fraction of the critical step used when run.dt = 0")
      .flag("run.force_dt", at(&Config::force_dt), false, "accept a run.dt above the critical step")
      .text("run.output", at(&Config::output), "rondel-output", "path", "output directory (must not exist unless run.overwrite)")
      .flag("run.overwrite", at(&Config::overwrite), false, "reuse an existing output directory")
      .flag("run.take_lock", at(&Config::take_lock), false,
            "take over the output directory's lock file when it names another host (whose run is gone, e.g. a "
            "failed node); a live run on this host is never taken over")
      .flag("run.progress", at(&Config::progress), true, "progress line on rank 0")
      .number("run.max_overlap", at(&Config::max_overlap), 0.1, "-", kPositive, "stop when an overlap exceeds this fraction of the smaller radius")
      .flag("run.reset_history", at(&Config::reset_history), false, "start from a file whose laws differ: drop its contact history")
      .flag("run.accept_materials", at(&Config::accept_materials), false, "start from a file whose material table differs: the discs "
                                                                         "keep their material index and take mass and inertia from this configuration")
      .number("run.max_residual", at(&Config::max_residual), 0.5, "-", Range{1e-9, INFINITY, false, true},
              "stop when the energy ledger residual exceeds this fraction of the energy scale (rounding alone reaches 1e-16)")
      .number("run.max_energy_gain", at(&Config::max_energy_gain), 0.1, "-", kPositive,
              "stop when the contacts have created more than this fraction of the energy scale (D_other fallen that far "
              "below its peak: a closed spring-dashpot cannot do positive work; a step above critical does)")
      .number("run.local_damping", at(&Config::local_damping), 0.0, "-", Range{0.0, 1.0, false, true},
              "local (non-viscous) damping alpha: each component of a free disc's force and its torque less alpha "
              "|F_i| sign(v_i), against its motion; not objective (a moving or turning sample is damped too); 0 = off");
  Keys(out, keys, readers)
      .number("output.snapshot_every", at(&Config::snapshot_every), I64{0}, "steps", kCount, "snapshot interval; 0 = none")
      .words("output.snapshot_fields", at(&Config::snapshot_fields), "position velocity omega radius flags rank", "-",
             "snapshot datasets (position is always written)", snapshot_field_names())
      .number("output.checkpoint_every", at(&Config::checkpoint_every), I64{0}, "steps", kCount,
              "checkpoint interval; 0 = none (see checkpoint_minutes)")
      .number("output.checkpoint_minutes", at(&Config::checkpoint_minutes), 0.0, "min", kNonNegative,
              "checkpoint also after this much wall time; 0 = off")
      .number("output.checkpoint_keep", at(&Config::checkpoint_keep), 2, "-", kAtLeastOne, "newest checkpoints kept")
      .flag("output.checkpoint_at_end", at(&Config::checkpoint_at_end), true, "write a checkpoint after the last step")
      .flag("output.verify_checkpoints", at(&Config::verify_checkpoints), true, "read each checkpoint back (checksums) before older ones go")
      .number("output.thermo_every", at(&Config::thermo_every), I64{5000}, "steps", kCount,
              "thermo line (step, time, KE, contacts, ledger residual, rate) on the terminal and in log.txt, at "
              "the diagnostics steps that are multiples of it and at the last step; 0 = off")
      .choice("output.final_format", at(&Config::final_format), "hex", kFinalFormats, "floats of final.csv");
  Keys(diag, keys, readers)
      .number("diagnostics.every", at(&Config::diag_every), I64{100}, "steps", kAtLeastOne, "interval of diagnostics.csv rows");
  // clang-format on
  all.add(run).add(out).add(diag);
}

void add_body_sections(po::options_description& all, std::vector<KeySpec>& keys, Readers* readers) {
  po::options_description domain("[domain]"), cell("[cell] a periodic cell that deforms (docs/physics.md section 10)"),
      grav("[gravity]"), mat("[material] the one material of a run (several: [material.NAME], below)");
  const std::string box = " (the simulation box)";
  // clang-format off
  Keys(domain, keys, readers)
      .number_without_default("domain.xlo", at(&Config::domain, &Domain::xlo), "m", kFinite, "box lower x", true, box)
      .number_without_default("domain.xhi", at(&Config::domain, &Domain::xhi), "m", kFinite, "box upper x, > domain.xlo", true, box)
      .number_without_default("domain.ylo", at(&Config::domain, &Domain::ylo), "m", kFinite, "box lower y", true, box)
      .number_without_default("domain.yhi", at(&Config::domain, &Domain::yhi), "m", kFinite, "box upper y, > domain.ylo", true, box)
      .flag("domain.periodic_x", at(&Config::domain, &Domain::periodic_x), false, "periodic in x")
      .flag("domain.periodic_y", at(&Config::domain, &Domain::periodic_y), false, "periodic in y");
  const std::string rate = " of the cell's velocity gradient (dh/dt = L h); needs domain.periodic_x and periodic_y";
  Keys(cell, keys, readers)
      .number("cell.rate_xx", at(&Config::domain, &Domain::L, &CellGradient::xx), 0.0, "1/s", kFinite, "L_xx: stretching in x" + rate)
      .number("cell.rate_xy", at(&Config::domain, &Domain::L, &CellGradient::xy), 0.0, "1/s", kFinite, "L_xy: the shear rate d(v_x)/dy, Lees-Edwards" + rate)
      .number("cell.rate_yy", at(&Config::domain, &Domain::L, &CellGradient::yy), 0.0, "1/s", kFinite, "L_yy: stretching in y" + rate)
      .flag("cell.flow_start", at(&Config::cell_flow_start), true, "a new run's discs start with the mean flow's velocity L (x - x0) added (a file scene's, to their velocity apart from the file's own flow)")
      .number("cell.stress_xx", at(&Config::cell_stress_xx), 0.0, "Pa", kNonNegative, "target contact stress S_xx (compression positive) held by the servo instead of cell.rate_xx; 0 = none")
      .number("cell.stress_yy", at(&Config::cell_stress_yy), 0.0, "Pa", kNonNegative, "target contact stress S_yy (compression positive) held by the servo instead of cell.rate_yy; 0 = none")
      .number("cell.servo_gain", at(&Config::cell_servo_gain), 0.0, "1/s", kNonNegative, "servo: L_ii = gain (S_ii - target) / target; > 0 with a stress target")
      .number("cell.servo_max_rate", at(&Config::cell_servo_max_rate), 1.0, "1/s", kNonNegative, "servo: the largest |L_ii| it sets");
  Keys(grav, keys, readers)
      .number("gravity.x", at(&Config::gravity, &Vec2::x), 0.0, "m/s^2", kGravity, "gravity x")
      .number("gravity.y", at(&Config::gravity, &Vec2::y), 0.0, "m/s^2", kGravity, "gravity y");
  // clang-format on
  config::declare_material_keys(mat, keys, "material", false);
  all.add(domain).add(cell).add(grav).add(mat);
}

// The help of one law parameter, "(required)" added (KeyTable adds the unit and range).
std::string param_help(const ParamSpec& p) {
  std::string s = p.help;
  if (p.presence == Presence::required) s += " (required)";
  return s;
}

// The words of contact.<kind>: its laws, in registry order.
std::vector<Choice<std::string>> law_choices(const LawKind& kind) {
  std::vector<Choice<std::string>> out;
  for (const LawInfo& law : kind.laws) out.push_back({law.keyword, law.keyword});
  return out;
}

// [contact] (one key per kind, its laws listed), then every law block, then [wall_contact]. The law blocks'
// parameters fill ContactParams through their ParamSpec (ConfigLaws.cpp), the rest Config.
void add_law_sections(po::options_description& all, std::vector<KeySpec>& keys, const LawCatalog& laws,
                      Readers* readers) {
  po::options_description contact("[contact]");
  std::string Config::*const selected[] = {&Config::normal_law, &Config::tangential_law, &Config::rolling_law};
  const auto kinds = laws.kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const auto words = law_choices(*kinds[k]);
    Keys(contact, keys, readers)
        .choice(std::string("contact.").append(kinds[k]->kind), at(selected[k]), kinds[k]->laws.front().keyword, words,
                std::string(kinds[k]->kind).append(" law"));
  }
  all.add(contact);
  for (const LawBlock* block : laws.blocks()) {
    po::options_description section(std::string("[").append(block->section).append("] ").append(block->title));
    for (const ParamSpec& p : block->params) {
      const std::string key = std::string(block->section).append(".").append(p.key);
      Keys table(section, keys);
      config::declare_law_param(table, key, p, true, param_help(p));
    }
    if (block == laws.bonds)
      Keys(section, keys, readers)
          .number("bonds.gap", at(&Config::bond_gap), 0.01, "-", kNonNegative,
                  "bond the discs whose gap at set-up is at most this fraction of the smaller radius")
          .text("bonds.file", at(&Config::bond_file), "", "path",
                "a CSV of the pairs to bond instead, 'gid1,gid2' per line (# comments, a header 'gid1,gid2'), each "
                "within bonds.gap; relative paths next to the INI file");
    all.add(section);
  }
  po::options_description wallc("[wall_contact] disc-wall parameters (default: the disc-disc ones)");
  // clang-format off
  Keys(wallc, keys)
      .declare_number<double>("wall_contact.k_n", std::nullopt, "N/m", kPositive, "normal stiffness at walls")
      .declare_number<double>("wall_contact.zeta", std::nullopt, "-", kNonNegative, "normal damping ratio at walls")
      .declare_number<double>("wall_contact.e", std::nullopt, "-", kRestitution, "restitution at walls")
      .declare_number<double>("wall_contact.k_s", std::nullopt, "N/m", kPositive, "tangential stiffness at walls")
      .declare_number<double>("wall_contact.mu", std::nullopt, "-", kNonNegative, "friction at walls")
      .declare_flag("wall_contact.rolling", true, "rolling resistance at walls (same law and parameters as discs)");
  // clang-format on
  all.add(wallc);
}

void add_wall_sections(po::options_description& all, std::vector<KeySpec>& keys, Readers* readers) {
  po::options_description neigh("[neighbour]"), par("[parallel]"), walls("[walls]");
  const auto wall = [](auto WallKeys::*member) { return at(&Config::wall_keys, member); };
  // clang-format off
  Keys(neigh, keys, readers).number("neighbour.skin", at(&Config::skin), 0.0, "m", kNonNegative, "Verlet skin; 0 = a quarter of the mean radius");
  Keys(par, keys, readers)
      .choice("parallel.partitioner", at(&Config::partitioner), Partitioners::choices().front().word, Partitioners::choices(),
              "cell-to-rank partitioner")
      .number("parallel.balance_every", at(&Config::balance_every), I64{1000}, "steps", kCount, "interval of load-balance checks; 0 = never")
      .number("parallel.balance_threshold", at(&Config::balance_threshold), 1.05, "-", Range{1.0, INFINITY, true, true},
              "repartition when max/mean work per rank exceeds this")
      .flag("parallel.force_balance", at(&Config::force_balance), false, "repartition at every check (testing)")
      .number("parallel.check_every", at(&Config::check_every), I64{10}, "steps", Range{1.0, 1000.0, false, false},
              "on several ranks and without servo, strain-rate or shear walls: the longest interval between two "
              "of the step's reductions (displacement check, error flags, signals); shorter when a bound on the discs' "
              "motion asks for it; 1 = every step");
  Keys(walls, keys, readers)
      .words("walls.box", wall(&WallKeys::box), "", "-", "box sides that are walls", box_side_words())
      .numbers("walls.box_region", wall(&WallKeys::box_region), "m", kFinite, "'xlo xhi ylo yhi' of the box walls; empty = the domain")
      .words("walls.control", wall(&WallKeys::control), "", "-", "box wall motions 'side:servo:STRESS' [Pa], 'side:strain_rate:RATE' [1/s, > 0 "
                                                              "compresses] and 'side:shear:VELOCITY' [m/s, along +x for bottom/top, +y for left/right], "
                                                              "e.g. 'top:strain_rate:0.05 left:servo:2e5 right:servo:2e5' or 'top:servo:1e5 top:shear:0.01'; "
                                                              "every number finite, a velocity below the speed of light")
      .words("walls.rough", wall(&WallKeys::rough), "", "-", "rough box walls; at the start of a stage the discs "
                                                          "whose centre lies within walls.rough_depth of such a wall are glued to it (they move with it)",
             box_side_words())
      .text("walls.material", wall(&WallKeys::material), "", "-", "material of every wall (a [material.NAME]); empty = the first material")
      .words("walls.materials", wall(&WallKeys::materials), "", "-", "box wall materials 'side:NAME ...', e.g. 'bottom:steel' (replace walls.material)")
      .words("walls.rough_materials", wall(&WallKeys::rough_materials), "", "-", "'side:NAME ...': the discs glued to that rough wall take material NAME")
      .number("walls.rough_depth", at(&Config::rough_depth), 0.0, "m", kNonNegative, "glue depth of walls.rough; 0 = the largest disc diameter")
      .number("walls.servo_gain", at(&Config::servo_gain), 0.2, "-", kOpenUnit, "servo gain: fraction of the force error closed per step")
      .number("walls.servo_max_speed", at(&Config::servo_max_speed), 0.1, "m/s", Range{0.0, config::kLightSpeed, true, false}, "largest servo wall speed");
  // The records of every wall kind (core/WallKinds.hpp), by Wall::Kind value.
  WallKinds::each([&]<class K>() {
    const auto code = static_cast<std::size_t>(K::kind);
    const config::Field<Config, std::vector<std::vector<double>>> records{
        [code](Config& c) -> std::vector<std::vector<double>>& {
          c.wall_keys.records.resize(WallKinds::size);
          return c.wall_keys.records[code];
        }};
    Keys(walls, keys, readers).records(K::key, records, K::unit, kFinite, K::help);
  });
  // clang-format on
  all.add(neigh).add(par).add(walls);
}

void add_scene_section(po::options_description& all, std::vector<KeySpec>& keys, Readers* readers) {
  po::options_description scene("[scene]");
  const auto s = [](auto SceneConfig::*member) { return at(&Config::scene, member); };
  // clang-format off
  Keys(scene, keys, readers)
      .choice("scene.type", s(&SceneConfig::type), "", scene_type_choices(), "how the discs are made")
      .number("scene.nx", s(&SceneConfig::nx), 0, "-", kCount, "lattice: discs per row")
      .number("scene.ny", s(&SceneConfig::ny), 0, "-", kCount, "lattice: rows")
      .number("scene.radius", s(&SceneConfig::radius), 0.0, "m", kNonNegative, "lattice: disc radius (> 0 for a lattice)")
      .number("scene.spacing", s(&SceneConfig::spacing), 0.0, "m", kNonNegative, "lattice: centre distance; 0 = 2 x radius")
      .number("scene.x0", s(&SceneConfig::x0), 0.0, "m", kFinite, "lattice: centre of the first disc, x")
      .number("scene.y0", s(&SceneConfig::y0), 0.0, "m", kFinite, "lattice: centre of the first disc, y")
      .number("scene.count", s(&SceneConfig::count), I64{0}, "-", kCount, "random, random_tiles: number of discs")
      .numbers("scene.region", s(&SceneConfig::region_given), "m", kFinite, "random, random_tiles: 'xlo xhi ylo yhi' region of the discs; empty = walls.box_region, else the domain")
      .choice("scene.distribution", s(&SceneConfig::distribution), "uniform_radius", kDistributions, "random, random_tiles: the radii")
      .number("scene.radius_min", s(&SceneConfig::radius_min), 0.0, "m", kNonNegative, "random, random_tiles: smallest radius")
      .number("scene.radius_max", s(&SceneConfig::radius_max), 0.0, "m", kNonNegative, "random, random_tiles: largest radius")
      .numbers("scene.sizes", s(&SceneConfig::sizes), "m", kPositive, "random, random_tiles, list: radii 'r1 r2 ...'")
      .numbers("scene.fractions", s(&SceneConfig::fractions), "-", kNonNegative, "random, random_tiles, list: number fractions 'f1 f2 ...' (sum 1)")
      .number("scene.seed", s(&SceneConfig::seed), I64{1}, "-", kCount, "random, random_tiles: seed (same scene on any rank count)")
      .number("scene.max_attempts", s(&SceneConfig::max_attempts), I64{1000}, "-", Range{1.0, 1e6, false, false}, "random, random_tiles: placement attempts per disc")
      .choice("scene.numbering", s(&SceneConfig::numbering), "placement", kNumberings, "random: the discs' ids")
      .text("scene.file", s(&SceneConfig::file), "", "path", "csv: 'id,x,y,radius[,vx,vy,omega]' rows, # comments; file: a Rondel "
                                                              "checkpoint or snapshot (.h5)")
      .number("scene.replicate_x", s(&SceneConfig::replicate_x), 1, "-", kAtLeastOne, "csv: periodic copies in x")
      .number("scene.replicate_y", s(&SceneConfig::replicate_y), 1, "-", kAtLeastOne, "csv: periodic copies in y")
      .number("scene.vx", at(&Config::scene, &SceneConfig::velocity, &Vec2::x), 0.0, "m/s", kSpeed, "initial velocity x of every disc (csv: added to the file's)")
      .number("scene.vy", at(&Config::scene, &SceneConfig::velocity, &Vec2::y), 0.0, "m/s", kSpeed, "initial velocity y")
      .number("scene.omega", s(&SceneConfig::omega), 0.0, "rad/s", kFinite, "initial angular velocity")
      .number("scene.max_initial_overlap", s(&SceneConfig::max_initial_overlap), 0.01, "-", Range{0.0, 1.0, false, false},
              "largest initial overlap allowed, / smaller radius")
      .words("scene.materials", s(&SceneConfig::material_words), "", "-", "lattice, random, random_tiles: the materials of the discs 'NAME1 NAME2 ...'; "
                                                                        "empty = the first material")
      .numbers("scene.material_fractions", s(&SceneConfig::material_fractions), "-", kNonNegative, "lattice, random, random_tiles: the fraction of each of "
                                                                                                  "scene.materials (sum 1); exact counts (largest remainder), placed by scene.seed")
      .choice("scene.material_by", s(&SceneConfig::material_by), "number", kMaterialBy, "what scene.material_fractions count")
      .numbers("scene.material_radius_min", s(&SceneConfig::material_radius_min), "m", kPositive,
               "random, random_tiles: smallest radius of each of scene.materials (replaces scene.radius_min)")
      .numbers("scene.material_radius_max", s(&SceneConfig::material_radius_max), "m", kPositive,
               "random, random_tiles: largest radius of each of scene.materials (replaces scene.radius_max)")
      .words("scene.size_materials", s(&SceneConfig::size_material_words), "", "-", "random, random_tiles, list: the material of each of scene.sizes "
                                                                                  "'NAME1 NAME2 ...'; csv: a last column 'material' (a name) after radius or omega");
  // clang-format on
  all.add(scene);
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

namespace config {

void declare_fixed_keys(const LawCatalog& laws, po::options_description& all, std::vector<KeySpec>& keys,
                        std::vector<KeyReader<Config>>* readers) {
  add_run_sections(all, keys, readers);
  add_body_sections(all, keys, readers);
  add_law_sections(all, keys, laws, readers);
  add_wall_sections(all, keys, readers);
  add_scene_section(all, keys, readers);
}

}  // namespace config

po::options_description config_schema(const LawCatalog& laws) {
  po::options_description all;
  std::vector<KeySpec> keys;
  config::declare_fixed_keys(laws, all, keys);
  return all;
}

std::vector<KeySpec> config_keys(const LawCatalog& laws, const DynamicSections& dynamic) {
  po::options_description all;
  std::vector<KeySpec> keys;
  config::declare_fixed_keys(laws, all, keys);
  config::declare_dynamic_keys(laws, dynamic, false, all, keys);
  return keys;
}

std::string closest_key(const std::string& name, const std::vector<KeySpec>& keys) {
  std::string best;
  std::size_t best_distance = name.size() / 3 + 2;  // closer than this, or no suggestion
  for (const KeySpec& k : keys) {
    const std::size_t d = edit_distance(name, k.key);
    if (d < best_distance) best = k.key, best_distance = d;
  }
  return best;
}

}  // namespace rondel
