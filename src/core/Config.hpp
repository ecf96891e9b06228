#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/Domain.hpp"
#include "core/Material.hpp"
#include "core/Vec2.hpp"
#include "core/Wall.hpp"

namespace rondel {

struct SceneConfig {
  std::string type;  // lattice_square, lattice_hex, random, csv
  // lattice
  int nx = 0, ny = 0;
  double radius = 0.0, spacing = 0.0, x0 = 0.0, y0 = 0.0;
  // random
  std::int64_t count = 0;
  double region[4] = {0, 0, 0, 0};  // xlo xhi ylo yhi
  std::string distribution;         // uniform_radius, uniform_area, list
  double radius_min = 0.0, radius_max = 0.0;
  std::vector<double> sizes, fractions;
  std::uint64_t seed = 1;
  std::int64_t max_attempts = 0;
  std::string numbering = "placement";  // placement (largest first) | rows (docs/benchmarks.md)
  // csv
  std::string file;
  int replicate_x = 1, replicate_y = 1;
  // every scene
  Vec2 velocity;
  double omega = 0.0;
  double max_initial_overlap = 0.0;  // fraction of the smaller radius
  // materials (docs/physics.md section 7): the material of each disc, by index into Config::materials
  std::vector<int> materials;                                    // scene.materials (empty: every disc has material 0)
  std::vector<double> material_fractions;                        // lattice, random: number fractions (sum 1)
  std::string material_by = "number";                            // number | area: what the fractions count
  std::vector<double> material_radius_min, material_radius_max;  // random: a radius range per material
  std::vector<int> size_materials;   // random, list: the material of each size (scene.size_materials)
  std::vector<int> rough_materials;  // per box side (bottom left right top): the material of glued discs; -1 keep
  std::vector<std::string> material_names;  // of Config::materials (a csv scene names them in a column)
};

struct Config {
  // [run]
  std::int64_t steps = 0;
  double dt = 0.0;  // 0: automatic
  double safety = 0.2;
  bool force_dt = false;
  std::string output;
  bool overwrite = false;
  bool progress = true;
  double max_overlap = 0.1;
  double max_residual = 0.5;
  double max_energy_gain = 0.1;  // run.max_energy_gain: largest -D_other / energy scale
  double local_damping = 0.0;    // alpha of the integrator's local damping, [0, 1); 0 = off
  bool reset_history = false;
  bool accept_materials = false;  // a restart or file scene may have a material table other than the file's
  // [output]
  std::int64_t snapshot_every = 0;
  std::vector<std::string> snapshot_fields;
  std::int64_t checkpoint_every = 0;
  double checkpoint_minutes = 0.0;
  int checkpoint_keep = 2;
  bool checkpoint_at_end = true;
  bool verify_checkpoints = true;    // each checkpoint read back before it replaces older ones
  std::int64_t thermo_every = 5000;  // thermo line interval in steps (at diagnostics steps); 0 = off
  std::string final_format = "hex";  // final.csv floats: hex or decimal
  std::string resume_dir;            // --resume DIR (command line only)
  // [diagnostics]
  std::int64_t diag_every = 100;
  // [domain], [gravity], [material] or [material.NAME]
  Domain domain;
  Vec2 gravity;
  double density = 0.0, thickness = 1.0;  // of material 0; the thickness is every material's
  std::vector<Material> materials;        // one ([material]) or several ([material.NAME], ordered by name)
  // [contact] and law blocks
  std::string normal_law, tangential_law, rolling_law;
  ContactParamTable params;
  // [neighbour]
  double skin = 0.0;  // 0: automatic
  // [parallel]
  std::string partitioner = "sfc";
  std::int64_t balance_every = 1000;
  double balance_threshold = 1.05;
  bool force_balance = false;
  std::int64_t check_every = 10;
  // [walls]
  WallSet walls;
  std::vector<std::string> box_walls;
  double servo_gain = 0.2, servo_max_speed = 0.1;
  double rough_depth = 0.0;  // [m] glue discs whose centre is closer than this to a rough wall; 0 = 2 R_max
  SceneConfig scene;

  std::string source_file;    // the INI file ("" when none)
  std::string resolved_text;  // every key with its value, in INI form
};

// Thrown for --help: the text to print.
struct HelpRequested {
  std::string text;
};

struct LawCatalog;

// Parses `rondel [FILE.ini] [--section.key=value ...]` with the laws of `laws` (their keywords, blocks and
// parameters). Throws ConfigError naming the key on bad input, HelpRequested for --help.
// physics/LawRegistry.hpp declares the same functions without the first argument, with the registry's
// catalog: parse_config(argc, argv), parse_config_text(ini, overrides), config_help().
Config parse_config(const LawCatalog& laws, int argc, const char* const* argv);
// The same from an INI text (tests): `overrides` are command-line style ("--run.steps=10").
Config parse_config_text(const LawCatalog& laws, const std::string& ini,
                         const std::vector<std::string>& overrides = {});
// The reference of every key (rondel --help).
std::string config_help(const LawCatalog& laws);

}  // namespace rondel
