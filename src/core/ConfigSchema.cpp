#include "core/ConfigSchema.hpp"

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace rondel {

namespace po = boost::program_options;

// The key lists below keep one key per line (clang-format would run them together).
namespace {
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

void add_run_sections(po::options_description& all) {
  // clang-format off
  po::options_description run("[run]");
  run.add_options()
      ("run.steps", def<std::int64_t>(1000), "[-] number of time steps")
      ("run.dt", def(0.0), "[s] time step; 0 = safety x critical step")
      ("run.safety", def(0.2), "[-] fraction of the critical step used when run.dt = 0, in (0, 1]")
      ("run.force_dt", def(false), "[-] accept a run.dt above the critical step")
      ("run.output", def("rondel-output"), "[path] output directory (must not exist unless run.overwrite)")
      ("run.overwrite", def(false), "[-] reuse an existing output directory")
      ("run.progress", def(true), "[-] progress line on rank 0")
      ("run.max_overlap", def(0.1), "[-] stop when an overlap exceeds this fraction of the smaller radius")
      ("run.reset_history", def(false), "[-] start from a file whose laws differ: drop its contact history")
      ("run.accept_materials", def(false), "[-] start from a file whose material table differs: the discs keep their "
                                           "material index and take mass and inertia from this configuration")
      ("run.max_residual", def(0.5), "[-] stop when the energy ledger residual exceeds this fraction of the energy scale")
      ("run.max_energy_gain", def(0.1), "[-] stop when the contacts have created more than this fraction of the energy "
                                        "scale (D_other fallen that far below its peak: a closed spring-dashpot cannot "
                                        "do positive work; a step above critical does)")
      ("run.local_damping", def(0.0), "[-] local (non-viscous) damping alpha in [0, 1): each component of a free disc's "
                                      "force and its torque less alpha |F_i| sign(v_i), against its motion; not objective "
                                      "(a moving or turning sample is damped too); 0 = off");
  po::options_description out("[output] snapshots and checkpoints (HDF5, FORMAT.md)");
  out.add_options()
      ("output.snapshot_every", def<std::int64_t>(0), "[steps] snapshot interval; 0 = none")
      ("output.snapshot_fields", def("position velocity omega radius flags rank"),
       "[-] snapshot datasets: any of gid material radius mass inertia position velocity theta omega force torque flags rank")
      ("output.checkpoint_every", def<std::int64_t>(0), "[steps] checkpoint interval; 0 = none (see checkpoint_minutes)")
      ("output.checkpoint_minutes", def(0.0), "[min] checkpoint also after this much wall time; 0 = off")
      ("output.checkpoint_keep", def(2), "[-] newest checkpoints kept, >= 1")
      ("output.checkpoint_at_end", def(true), "[-] write a checkpoint after the last step")
      ("output.thermo_every", def<std::int64_t>(5000),
       "[steps] thermo line (step, time, KE, contacts, ledger residual, rate) on the terminal and in log.txt, at "
       "the diagnostics steps that are multiples of it and at the last step; 0 = off")
      ("output.final_format", def("hex"),
       "[-] floats of final.csv: hex (C99 %a, bit-exact) or decimal (%.17g, reads back to the same bits)");
  po::options_description diag("[diagnostics]");
  diag.add_options()("diagnostics.every", def<std::int64_t>(100), "[steps] interval of diagnostics.csv rows");
  // clang-format on
  all.add(run).add(out).add(diag);
}

void add_body_sections(po::options_description& all) {
  // clang-format off
  po::options_description domain("[domain]");
  domain.add_options()
      ("domain.xlo", opt<double>(), "[m] box lower x (required)")
      ("domain.xhi", opt<double>(), "[m] box upper x (required)")
      ("domain.ylo", opt<double>(), "[m] box lower y (required)")
      ("domain.yhi", opt<double>(), "[m] box upper y (required)")
      ("domain.periodic_x", def(false), "[-] periodic in x")
      ("domain.periodic_y", def(false), "[-] periodic in y");
  po::options_description grav("[gravity]");
  grav.add_options()("gravity.x", def(0.0), "[m/s^2] gravity x")("gravity.y", def(0.0), "[m/s^2] gravity y");
  po::options_description mat("[material] the one material of a run (several: [material.NAME], below)");
  mat.add_options()
      ("material.density", def(2650.0), "[kg/m^3] disc density")
      ("material.thickness", def(1.0), "[m] disc thickness t (forces and energies are per t)")
      ("material.body", def("disc"), "[-] disc (m = rho pi R^2 t, I = m R^2/2) | sphere (m = 4/3 pi rho R^3, I = 2/5 m R^2)")
      ("material.youngs_modulus", opt<double>(), "[Pa] Young's modulus E (required with contact.normal = hertz)")
      ("material.poisson_ratio", opt<double>(), "[-] Poisson's ratio nu, in (-1, 0.5) (required with contact.normal = hertz)");
  // clang-format on
  all.add(domain).add(grav).add(mat);
}

// "[unit] help (required), RANGE" for one law parameter. (Built by appending: GCC 12 warns falsely,
// -Wrestrict, on "literal" + std::string here.)
std::string param_help(const ParamSpec& p) {
  std::string s = "[";
  s.append(p.unit).append("] ").append(p.help);
  if (p.presence == Presence::required) s += " (required)";
  return s.append(", ").append(p.range.text());
}

// [contact] (one key per kind, its laws listed), then every law block, then [wall_contact].
void add_law_sections(po::options_description& all, const LawCatalog& laws) {
  po::options_description contact("[contact]");
  for (const LawKind* kind : laws.kinds()) {
    const std::string key = std::string("contact.").append(kind->kind);
    const std::string help = std::string("[-] ").append(kind->kind).append(" law: ").append(kind->keywords());
    contact.add_options()(key.c_str(), def(kind->laws.front().keyword), help.c_str());
  }
  all.add(contact);
  for (const LawBlock* block : laws.blocks()) {
    po::options_description section(std::string("[").append(block->section).append("] ").append(block->title));
    for (const ParamSpec& p : block->params) {
      const std::string key = std::string(block->section).append(".").append(p.key);
      if (p.presence == Presence::defaulted)
        section.add_options()(key.c_str(), def(p.def), param_help(p).c_str());
      else
        section.add_options()(key.c_str(), opt<double>(), param_help(p).c_str());
    }
    all.add(section);
  }
  // clang-format off
  po::options_description wallc("[wall_contact] disc-wall parameters (default: the disc-disc ones)");
  wallc.add_options()
      ("wall_contact.k_n", opt<double>(), "[N/m] normal stiffness at walls")
      ("wall_contact.zeta", opt<double>(), "[-] normal damping ratio at walls")
      ("wall_contact.e", opt<double>(), "[-] restitution at walls, in (0, 1]")
      ("wall_contact.k_s", opt<double>(), "[N/m] tangential stiffness at walls")
      ("wall_contact.mu", opt<double>(), "[-] friction at walls >= 0")
      ("wall_contact.rolling", def(true), "[-] rolling resistance at walls (same law and parameters as discs)");
  // clang-format on
  all.add(wallc);
}

void add_wall_sections(po::options_description& all) {
  // clang-format off
  po::options_description neigh("[neighbour]");
  neigh.add_options()("neighbour.skin", def(0.0), "[m] Verlet skin; 0 = a quarter of the mean radius");
  po::options_description par("[parallel]");
  par.add_options()
      ("parallel.partitioner", def("sfc"),
       "[-] cell-to-rank partitioner: sfc (Hilbert-curve cuts, the default) | grid (blocks) | metis (graph "
       "partition; every rank holds the whole cell map: moderate sizes)")
      ("parallel.balance_every", def<std::int64_t>(1000), "[steps] interval of load-balance checks; 0 = never")
      ("parallel.balance_threshold", def(1.05), "[-] repartition when max/mean work per rank exceeds this, > 1")
      ("parallel.force_balance", def(false), "[-] repartition at every check (testing)")
      ("parallel.check_every", def<std::int64_t>(10),
       "[steps] on several ranks and without servo, strain-rate or shear walls: the longest interval between two "
       "of the step's reductions (displacement check, error flags, signals); shorter when a bound on the discs' "
       "motion asks for it; 1 = every step, 1 to 1000");
  po::options_description walls("[walls]");
  walls.add_options()
      ("walls.box", def(""), "[-] box sides that are walls: any of bottom left right top")
      ("walls.box_region", def(""), "[m] 'xlo xhi ylo yhi' of the box walls; empty = the domain")
      ("walls.control", def(""), "[-] box wall motions 'side:servo:STRESS' [Pa], 'side:strain_rate:RATE' [1/s, > 0 "
                                 "compresses] and 'side:shear:VELOCITY' [m/s, along +x for bottom/top, +y for left/right], "
                                 "e.g. 'top:strain_rate:0.05 left:servo:2e5 right:servo:2e5' or 'top:servo:1e5 top:shear:0.01'")
      ("walls.rough", def(""), "[-] rough box walls: any of bottom left right top; at the start of a stage the discs "
                               "whose centre lies within walls.rough_depth of such a wall are glued to it (they move with it)")
      ("walls.material", def(""), "[-] material of every wall (a [material.NAME]); empty = the first material")
      ("walls.materials", def(""), "[-] box wall materials 'side:NAME ...', e.g. 'bottom:steel' (replace walls.material)")
      ("walls.rough_materials", def(""), "[-] 'side:NAME ...': the discs glued to that rough wall take material NAME")
      ("walls.rough_depth", def(0.0), "[m] glue depth of walls.rough; 0 = the largest disc diameter")
      ("walls.servo_gain", def(0.2), "[-] servo gain in (0, 1): fraction of the force error closed per step")
      ("walls.servo_max_speed", def(0.1), "[m/s] largest servo wall speed")
      ("walls.lines", def(""), "[m, m/s, rad/s] infinite lines 'px py nx ny [vx vy | omega cx cy]; ...' (n points to "
                               "the discs; 'vx vy' translates the line, 'omega cx cy' rotates it about (cx, cy))")
      ("walls.segments", def(""), "[m, m/s, rad/s] segments 'x1 y1 x2 y2 [vx vy | omega cx cy]; ...' (a translation "
                                  "or a rotation about the fixed centre (cx, cy), counter-clockwise positive)")
      ("walls.circles", def(""), "[m, rad/s] circles 'cx cy R_c [omega]; ...' whose inside holds the discs (drums), "
                                 "rotating about their centre at omega (default 0); walls after walls.segments");
  // clang-format on
  all.add(neigh).add(par).add(walls);
}

void add_scene_section(po::options_description& all) {
  // clang-format off
  po::options_description scene("[scene]");
  scene.add_options()
      ("scene.type", opt<std::string>(), "[-] lattice_square | lattice_hex | random | csv | file (required)")
      ("scene.nx", def(0), "[-] lattice: discs per row")
      ("scene.ny", def(0), "[-] lattice: rows")
      ("scene.radius", def(0.0), "[m] lattice: disc radius")
      ("scene.spacing", def(0.0), "[m] lattice: centre distance; 0 = 2 x radius")
      ("scene.x0", def(0.0), "[m] lattice: centre of the first disc, x")
      ("scene.y0", def(0.0), "[m] lattice: centre of the first disc, y")
      ("scene.count", def<std::int64_t>(0), "[-] random: number of discs")
      ("scene.region", def(""), "[m] random: 'xlo xhi ylo yhi' region of the discs; empty = walls.box_region, else the domain")
      ("scene.distribution", def("uniform_radius"), "[-] random: uniform_radius | uniform_area | list")
      ("scene.radius_min", def(0.0), "[m] random: smallest radius")
      ("scene.radius_max", def(0.0), "[m] random: largest radius")
      ("scene.sizes", def(""), "[m] random, list: radii 'r1 r2 ...'")
      ("scene.fractions", def(""), "[-] random, list: number fractions 'f1 f2 ...' (sum 1)")
      ("scene.seed", def<std::uint64_t>(1), "[-] random: seed (same scene on any rank count)")
      ("scene.max_attempts", def<std::int64_t>(1000), "[-] random: placement attempts per disc")
      ("scene.file", def(""), "[path] csv: 'id,x,y,radius[,vx,vy,omega]' rows, # comments; file: a Rondel "
                               "checkpoint or snapshot (.h5)")
      ("scene.replicate_x", def(1), "[-] csv: periodic copies in x")
      ("scene.replicate_y", def(1), "[-] csv: periodic copies in y")
      ("scene.vx", def(0.0), "[m/s] initial velocity x of every disc (csv: added to the file's)")
      ("scene.vy", def(0.0), "[m/s] initial velocity y")
      ("scene.omega", def(0.0), "[rad/s] initial angular velocity")
      ("scene.max_initial_overlap", def(0.01), "[-] largest initial overlap allowed, / smaller radius")
      ("scene.materials", def(""), "[-] lattice, random: the materials of the discs 'NAME1 NAME2 ...'; empty = the first material")
      ("scene.material_fractions", def(""), "[-] lattice, random: the fraction of each of scene.materials (sum 1); "
                                            "exact counts (largest remainder), placed by scene.seed")
      ("scene.material_by", def("number"), "[-] what scene.material_fractions count: number | area")
      ("scene.material_radius_min", def(""), "[m] random: smallest radius of each of scene.materials (replaces scene.radius_min)")
      ("scene.material_radius_max", def(""), "[m] random: largest radius of each of scene.materials (replaces scene.radius_max)")
      ("scene.size_materials", def(""), "[-] random, list: the material of each of scene.sizes 'NAME1 NAME2 ...'; "
                                        "csv: a last column 'material' (a name) after radius or omega");
  // clang-format on
  all.add(scene);
}

}  // namespace

po::options_description config_schema(const LawCatalog& laws) {
  po::options_description all;
  add_run_sections(all);
  add_body_sections(all);
  add_law_sections(all, laws);
  add_wall_sections(all);
  add_scene_section(all);
  return all;
}

}  // namespace rondel
