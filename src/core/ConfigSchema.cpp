#include "core/ConfigSchema.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "core/ConfigRead.hpp"

namespace rondel {

namespace po = boost::program_options;

namespace config {

KeyTable& KeyTable::flag(const std::string& key, po::typed_value<bool>* value, const std::string& help) {
  keys_.push_back({key, KeyType::flag, kFinite});
  return add(key, value, "-", help + " (true | false)", kFinite, "");
}

KeyTable& KeyTable::text(const std::string& key, po::typed_value<std::string>* value, const char* unit,
                         const std::string& help) {
  keys_.push_back({key, KeyType::text, kFinite});
  return add(key, value, unit, help, kFinite, "");
}

KeyTable& KeyTable::list(const std::string& key, const char* unit, const Range& each, const std::string& help,
                         bool records) {
  keys_.push_back({key, records ? KeyType::records : KeyType::numbers, each});
  return add(key, po::value<std::string>()->default_value(""), unit, help, each, "each number ");
}

KeyTable& KeyTable::add(const std::string& key, const po::value_semantic* value, const char* unit,
                        const std::string& help, const Range& range, const char* each) {
  std::string line = "[";
  line.append(unit).append("] ").append(help);
  if (std::isfinite(range.lo) || std::isfinite(range.hi)) line.append(", ").append(each).append(range.text());
  options_.add_options()(key.c_str(), value, line.c_str());
  return *this;
}

}  // namespace config

namespace {

using config::KeyTable;
using config::kFinite;
using config::kGravity;
using config::kSpeed;

template <class T>
po::typed_value<T>* def(T v) {
  return po::value<T>()->default_value(v);
}
// Doubles print their shortest form in --help ("0.2", not "0.20000000000000001").
po::typed_value<double>* def(double v) {
  std::ostringstream text;
  text << v;
  return po::value<double>()->default_value(v, text.str());
}
po::typed_value<std::string>* def(const char* v) { return po::value<std::string>()->default_value(v); }
template <class T>
po::typed_value<T>* opt() {
  return po::value<T>();
}

// Ranges used by several keys below.
constexpr Range kCount{0.0, INFINITY, false, true};       // an integer >= 0
constexpr Range kAtLeastOne{1.0, INFINITY, false, true};  // an integer >= 1
constexpr Range kFraction{0.0, 1.0, true, false};         // in (0, 1]
constexpr Range kOpenUnit{0.0, 1.0, true, true};          // in (0, 1)
// run.steps: t = step x dt keeps every step's increment (below 2^52 steps); more would run for years.
constexpr Range kSteps{0.0, 1e15, false, false};

// The key lists below keep one key per line (clang-format would run them together).
void add_run_sections(po::options_description& all, std::vector<KeySpec>& keys) {
  po::options_description run("[run]"), out("[output] snapshots and checkpoints (HDF5, FORMAT.md)"),
      diag("[diagnostics]");
  // clang-format off
  KeyTable(run, keys)
      .number("run.steps", def<std::int64_t>(1000), "-", kSteps, "number of time steps")
      .number("run.dt", def(0.0), "s", kNonNegative, "time step; 0 = safety x critical step")
      .number("run.safety", def(0.2), "-", kFraction, "fraction of the critical step used when run.dt = 0")
      .flag("run.force_dt", def(false), "accept a run.dt above the critical step")
      .text("run.output", def("rondel-output"), "path", "output directory (must not exist unless run.overwrite)")
      .flag("run.overwrite", def(false), "reuse an existing output directory")
      .flag("run.progress", def(true), "progress line on rank 0")
      .number("run.max_overlap", def(0.1), "-", kPositive, "stop when an overlap exceeds this fraction of the smaller radius")
      .flag("run.reset_history", def(false), "start from a file whose laws differ: drop its contact history")
      .flag("run.accept_materials", def(false), "start from a file whose material table differs: the discs keep their "
                                                "material index and take mass and inertia from this configuration")
      .number("run.max_residual", def(0.5), "-", Range{1e-9, INFINITY, false, true}, "stop when the energy ledger residual exceeds this fraction of the energy scale")
      .number("run.max_energy_gain", def(0.1), "-", kPositive, "stop when the contacts have created more than this fraction of the energy "
                                                              "scale (D_other fallen that far below its peak: a closed spring-dashpot cannot "
                                                              "do positive work; a step above critical does)")
      .number("run.local_damping", def(0.0), "-", Range{0.0, 1.0, false, true},
              "local (non-viscous) damping alpha: each component of a free disc's force and its torque less alpha "
              "|F_i| sign(v_i), against its motion; not objective (a moving or turning sample is damped too); 0 = off");
  KeyTable(out, keys)
      .number("output.snapshot_every", def<std::int64_t>(0), "steps", kCount, "snapshot interval; 0 = none")
      .text("output.snapshot_fields", def("position velocity omega radius flags rank"), "-",
            "snapshot datasets: any of gid material radius mass inertia position velocity theta omega force torque flags rank")
      .number("output.checkpoint_every", def<std::int64_t>(0), "steps", kCount, "checkpoint interval; 0 = none (see checkpoint_minutes)")
      .number("output.checkpoint_minutes", def(0.0), "min", kNonNegative, "checkpoint also after this much wall time; 0 = off")
      .number("output.checkpoint_keep", def(2), "-", kAtLeastOne, "newest checkpoints kept")
      .flag("output.checkpoint_at_end", def(true), "write a checkpoint after the last step")
      .flag("output.verify_checkpoints", def(true), "read each checkpoint back (checksums) before older ones go")
      .number("output.thermo_every", def<std::int64_t>(5000), "steps", kCount,
              "thermo line (step, time, KE, contacts, ledger residual, rate) on the terminal and in log.txt, at "
              "the diagnostics steps that are multiples of it and at the last step; 0 = off")
      .text("output.final_format", def("hex"), "-",
            "floats of final.csv: hex (C99 %a, bit-exact) or decimal (%.17g, reads back to the same bits)");
  KeyTable(diag, keys).number("diagnostics.every", def<std::int64_t>(100), "steps", kAtLeastOne, "interval of diagnostics.csv rows");
  // clang-format on
  all.add(run).add(out).add(diag);
}

void add_body_sections(po::options_description& all, std::vector<KeySpec>& keys) {
  po::options_description domain("[domain]"), grav("[gravity]"),
      mat("[material] the one material of a run (several: [material.NAME], below)");
  // clang-format off
  KeyTable(domain, keys)
      .number("domain.xlo", opt<double>(), "m", kFinite, "box lower x (required)")
      .number("domain.xhi", opt<double>(), "m", kFinite, "box upper x (required), > domain.xlo")
      .number("domain.ylo", opt<double>(), "m", kFinite, "box lower y (required)")
      .number("domain.yhi", opt<double>(), "m", kFinite, "box upper y (required), > domain.ylo")
      .flag("domain.periodic_x", def(false), "periodic in x")
      .flag("domain.periodic_y", def(false), "periodic in y");
  KeyTable(grav, keys)
      .number("gravity.x", def(0.0), "m/s^2", kGravity, "gravity x")
      .number("gravity.y", def(0.0), "m/s^2", kGravity, "gravity y");
  KeyTable(mat, keys)
      .number("material.density", def(2650.0), "kg/m^3", kPositive, "disc density")
      .number("material.thickness", def(1.0), "m", kPositive, "disc thickness t (forces and energies are per t)")
      .text("material.body", def("disc"), "-", "disc (m = rho pi R^2 t, I = m R^2/2) | sphere (m = 4/3 pi rho R^3, I = 2/5 m R^2)")
      .number("material.youngs_modulus", opt<double>(), "Pa", kPositive, "Young's modulus E (required with contact.normal = hertz)")
      .number("material.poisson_ratio", opt<double>(), "-", Range{-1.0, 0.5, true, true},
              "Poisson's ratio nu (required with contact.normal = hertz)");
  // clang-format on
  all.add(domain).add(grav).add(mat);
}

// The help of one law parameter, "(required)" added (KeyTable adds the unit and range).
std::string param_help(const ParamSpec& p) {
  std::string s = p.help;
  if (p.presence == Presence::required) s += " (required)";
  return s;
}

// [contact] (one key per kind, its laws listed), then every law block, then [wall_contact].
void add_law_sections(po::options_description& all, std::vector<KeySpec>& keys, const LawCatalog& laws) {
  po::options_description contact("[contact]");
  for (const LawKind* kind : laws.kinds()) {
    const std::string key = std::string("contact.").append(kind->kind);
    const std::string help = std::string(kind->kind).append(" law: ").append(kind->keywords());
    KeyTable(contact, keys).text(key, def(kind->laws.front().keyword), "-", help);
  }
  all.add(contact);
  for (const LawBlock* block : laws.blocks()) {
    po::options_description section(std::string("[").append(block->section).append("] ").append(block->title));
    for (const ParamSpec& p : block->params) {
      const std::string key = std::string(block->section).append(".").append(p.key);
      KeyTable(section, keys)
          .number(key, p.presence == Presence::defaulted ? def(p.def) : opt<double>(), p.unit, p.range, param_help(p));
    }
    all.add(section);
  }
  po::options_description wallc("[wall_contact] disc-wall parameters (default: the disc-disc ones)");
  // clang-format off
  KeyTable(wallc, keys)
      .number("wall_contact.k_n", opt<double>(), "N/m", kPositive, "normal stiffness at walls")
      .number("wall_contact.zeta", opt<double>(), "-", kNonNegative, "normal damping ratio at walls")
      .number("wall_contact.e", opt<double>(), "-", kRestitution, "restitution at walls")
      .number("wall_contact.k_s", opt<double>(), "N/m", kPositive, "tangential stiffness at walls")
      .number("wall_contact.mu", opt<double>(), "-", kNonNegative, "friction at walls")
      .flag("wall_contact.rolling", def(true), "rolling resistance at walls (same law and parameters as discs)");
  // clang-format on
  all.add(wallc);
}

void add_wall_sections(po::options_description& all, std::vector<KeySpec>& keys) {
  po::options_description neigh("[neighbour]"), par("[parallel]"), walls("[walls]");
  // clang-format off
  KeyTable(neigh, keys).number("neighbour.skin", def(0.0), "m", kNonNegative, "Verlet skin; 0 = a quarter of the mean radius");
  KeyTable(par, keys)
      .text("parallel.partitioner", def("sfc"), "-",
            "cell-to-rank partitioner: sfc (Hilbert-curve cuts, the default) | grid (blocks) | metis (graph "
            "partition; every rank holds the whole cell map: moderate sizes)")
      .number("parallel.balance_every", def<std::int64_t>(1000), "steps", kCount, "interval of load-balance checks; 0 = never")
      .number("parallel.balance_threshold", def(1.05), "-", Range{1.0, INFINITY, true, true},
              "repartition when max/mean work per rank exceeds this")
      .flag("parallel.force_balance", def(false), "repartition at every check (testing)")
      .number("parallel.check_every", def<std::int64_t>(10), "steps", Range{1.0, 1000.0, false, false},
              "on several ranks and without servo, strain-rate or shear walls: the longest interval between two "
              "of the step's reductions (displacement check, error flags, signals); shorter when a bound on the discs' "
              "motion asks for it; 1 = every step");
  KeyTable(walls, keys)
      .text("walls.box", def(""), "-", "box sides that are walls: any of bottom left right top")
      .list("walls.box_region", "m", kFinite, "'xlo xhi ylo yhi' of the box walls; empty = the domain")
      .text("walls.control", def(""), "-", "box wall motions 'side:servo:STRESS' [Pa], 'side:strain_rate:RATE' [1/s, > 0 "
                                          "compresses] and 'side:shear:VELOCITY' [m/s, along +x for bottom/top, +y for left/right], "
                                          "e.g. 'top:strain_rate:0.05 left:servo:2e5 right:servo:2e5' or 'top:servo:1e5 top:shear:0.01'; "
                                          "every number finite, a velocity below the speed of light")
      .text("walls.rough", def(""), "-", "rough box walls: any of bottom left right top; at the start of a stage the discs "
                                        "whose centre lies within walls.rough_depth of such a wall are glued to it (they move with it)")
      .text("walls.material", def(""), "-", "material of every wall (a [material.NAME]); empty = the first material")
      .text("walls.materials", def(""), "-", "box wall materials 'side:NAME ...', e.g. 'bottom:steel' (replace walls.material)")
      .text("walls.rough_materials", def(""), "-", "'side:NAME ...': the discs glued to that rough wall take material NAME")
      .number("walls.rough_depth", def(0.0), "m", kNonNegative, "glue depth of walls.rough; 0 = the largest disc diameter")
      .number("walls.servo_gain", def(0.2), "-", kOpenUnit, "servo gain: fraction of the force error closed per step")
      .number("walls.servo_max_speed", def(0.1), "m/s", Range{0.0, config::kLightSpeed, true, false}, "largest servo wall speed")
      .list("walls.lines", "m, m/s, rad/s", kFinite, "infinite lines 'px py nx ny [vx vy | omega cx cy]; ...' (n points to "
                                                      "the discs; 'vx vy' translates the line, 'omega cx cy' rotates it about (cx, cy))", true)
      .list("walls.segments", "m, m/s, rad/s", kFinite, "segments 'x1 y1 x2 y2 [vx vy | omega cx cy]; ...' (a translation "
                                                        "or a rotation about the fixed centre (cx, cy), counter-clockwise positive)", true)
      .list("walls.circles", "m, rad/s", kFinite, "circles 'cx cy R_c [omega]; ...' whose inside holds the discs (drums), "
                                                 "rotating about their centre at omega (default 0); walls after walls.segments", true);
  // clang-format on
  all.add(neigh).add(par).add(walls);
}

void add_scene_section(po::options_description& all, std::vector<KeySpec>& keys) {
  po::options_description scene("[scene]");
  // clang-format off
  KeyTable(scene, keys)
      .text("scene.type", opt<std::string>(), "-", "lattice_square | lattice_hex | random | csv | file (required)")
      .number("scene.nx", def(0), "-", kCount, "lattice: discs per row")
      .number("scene.ny", def(0), "-", kCount, "lattice: rows")
      .number("scene.radius", def(0.0), "m", kNonNegative, "lattice: disc radius (> 0 for a lattice)")
      .number("scene.spacing", def(0.0), "m", kNonNegative, "lattice: centre distance; 0 = 2 x radius")
      .number("scene.x0", def(0.0), "m", kFinite, "lattice: centre of the first disc, x")
      .number("scene.y0", def(0.0), "m", kFinite, "lattice: centre of the first disc, y")
      .number("scene.count", def<std::int64_t>(0), "-", kCount, "random: number of discs")
      .list("scene.region", "m", kFinite, "random: 'xlo xhi ylo yhi' region of the discs; empty = walls.box_region, else the domain")
      .text("scene.distribution", def("uniform_radius"), "-", "random: uniform_radius | uniform_area | list")
      .number("scene.radius_min", def(0.0), "m", kNonNegative, "random: smallest radius")
      .number("scene.radius_max", def(0.0), "m", kNonNegative, "random: largest radius")
      .list("scene.sizes", "m", kPositive, "random, list: radii 'r1 r2 ...'")
      .list("scene.fractions", "-", kNonNegative, "random, list: number fractions 'f1 f2 ...' (sum 1)")
      .number("scene.seed", def<std::int64_t>(1), "-", kCount, "random: seed (same scene on any rank count)")
      .number("scene.max_attempts", def<std::int64_t>(1000), "-", Range{1.0, 1e6, false, false}, "random: placement attempts per disc")
      .text("scene.numbering", def("placement"), "-", "random: the discs' ids: placement (the order they are placed, largest "
                                                     "first) | rows (in rows across the region, by x: faster beyond ~100,000 discs)")
      .text("scene.file", def(""), "path", "csv: 'id,x,y,radius[,vx,vy,omega]' rows, # comments; file: a Rondel "
                                           "checkpoint or snapshot (.h5)")
      .number("scene.replicate_x", def(1), "-", kAtLeastOne, "csv: periodic copies in x")
      .number("scene.replicate_y", def(1), "-", kAtLeastOne, "csv: periodic copies in y")
      .number("scene.vx", def(0.0), "m/s", kSpeed, "initial velocity x of every disc (csv: added to the file's)")
      .number("scene.vy", def(0.0), "m/s", kSpeed, "initial velocity y")
      .number("scene.omega", def(0.0), "rad/s", kFinite, "initial angular velocity")
      .number("scene.max_initial_overlap", def(0.01), "-", Range{0.0, 1.0, false, false}, "largest initial overlap allowed, / smaller radius")
      .text("scene.materials", def(""), "-", "lattice, random: the materials of the discs 'NAME1 NAME2 ...'; empty = the first material")
      .list("scene.material_fractions", "-", kNonNegative, "lattice, random: the fraction of each of scene.materials (sum 1); "
                                                         "exact counts (largest remainder), placed by scene.seed")
      .text("scene.material_by", def("number"), "-", "what scene.material_fractions count: number | area")
      .list("scene.material_radius_min", "m", kPositive, "random: smallest radius of each of scene.materials (replaces scene.radius_min)")
      .list("scene.material_radius_max", "m", kPositive, "random: largest radius of each of scene.materials (replaces scene.radius_max)")
      .text("scene.size_materials", def(""), "-", "random, list: the material of each of scene.sizes 'NAME1 NAME2 ...'; "
                                                 "csv: a last column 'material' (a name) after radius or omega");
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

void declare_fixed_keys(const LawCatalog& laws, po::options_description& all, std::vector<KeySpec>& keys) {
  add_run_sections(all, keys);
  add_body_sections(all, keys);
  add_law_sections(all, keys, laws);
  add_wall_sections(all, keys);
  add_scene_section(all, keys);
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
