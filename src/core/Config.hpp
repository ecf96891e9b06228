#pragma once
// The run's configuration, as the key table fills it (core/ConfigSchema.cpp declares every key once, with the
// field it fills, its default, range, unit and help; docs/design.md section 8). The defaults live in the rows,
// not here: a Config is made by parse_config only.
#include <cstdint>
#include <string>
#include <vector>

#include "core/ContactParams.hpp"
#include "core/Domain.hpp"
#include "core/Material.hpp"
#include "core/Vec2.hpp"
#include "core/Wall.hpp"

namespace rondel {

struct SceneType;  // core/SceneTypes.hpp: the scene builders' registry

enum class FinalFormat { hex, decimal };                         // output.final_format
enum class Distribution { uniform_radius, uniform_area, list };  // scene.distribution
enum class Numbering { placement, rows };                        // scene.numbering (docs/benchmarks.md)
enum class MaterialBy { number, area };                          // scene.material_by

struct SceneConfig {
  const SceneType* type = nullptr;  // scene.type (its row of the registry)
  // lattice
  int nx = 0, ny = 0;
  double radius = 0.0, spacing = 0.0, x0 = 0.0, y0 = 0.0;
  // random
  std::int64_t count = 0;
  std::vector<double> region_given;  // scene.region as given (empty: walls.box_region, else the domain)
  double region[4] = {0, 0, 0, 0};   // xlo xhi ylo yhi
  Distribution distribution = Distribution::uniform_radius;
  double radius_min = 0.0, radius_max = 0.0;
  std::vector<double> sizes, fractions;
  std::int64_t seed = 0;  // >= 0
  std::int64_t max_attempts = 0;
  Numbering numbering = Numbering::placement;
  // csv, file
  std::string file;
  int replicate_x = 1, replicate_y = 1;
  // every scene
  Vec2 velocity;
  double omega = 0.0;
  double max_initial_overlap = 0.0;  // fraction of the smaller radius
  // materials (docs/physics.md section 7): the material of each disc, by index into Config::materials
  std::vector<std::string> material_words;                       // scene.materials as given
  std::vector<int> materials;                                    // their indices (empty: every disc has material 0)
  std::vector<double> material_fractions;                        // lattice, random: number fractions (sum 1)
  MaterialBy material_by = MaterialBy::number;                   // what the fractions count
  std::vector<double> material_radius_min, material_radius_max;  // random: a radius range per material
  std::vector<std::string> size_material_words;                  // scene.size_materials as given
  std::vector<int> size_materials;                               // random, list: the material of each size
  std::vector<int> rough_materials;  // per box side (bottom left right top): the material of glued discs; -1 keep
  std::vector<std::string> material_names;  // of Config::materials (a csv scene names them in a column)
};

// The [walls] keys as given; ConfigWalls.cpp turns them into Config::walls.
struct WallKeys {
  std::vector<std::string> box, control, rough, materials, rough_materials;
  std::string material;
  std::vector<double> box_region;
  // The records of each wall kind's key (walls.lines, walls.segments, walls.circles), by Wall::Kind value.
  std::vector<std::vector<std::vector<double>>> records;
};

struct Config {
  // [run]
  std::int64_t steps = 0;
  double dt = 0.0;  // 0: safety x the critical step
  double safety = 0.0;
  bool force_dt = false;
  std::string output;
  bool overwrite = false;
  bool take_lock = false;  // take over a lock file of another host (its run is gone: a node that failed)
  std::string run_id;      // not a key: the run's identity (Simulation), in config.ini and every checkpoint
  bool progress = false;
  double max_overlap = 0.0;
  double max_residual = 0.0;
  double max_energy_gain = 0.0;  // largest -D_other / energy scale
  double local_damping = 0.0;    // alpha of the integrator's local damping, [0, 1); 0 = off
  bool reset_history = false;
  bool accept_materials = false;  // a restart or file scene may have a material table other than the file's
  // [output]
  std::int64_t snapshot_every = 0;
  std::vector<std::string> snapshot_fields;
  std::int64_t checkpoint_every = 0;
  double checkpoint_minutes = 0.0;
  int checkpoint_keep = 0;
  bool checkpoint_at_end = false;
  bool verify_checkpoints = false;  // each checkpoint read back before it replaces older ones
  std::int64_t thermo_every = 0;    // thermo line interval in steps (at diagnostics steps); 0 = off
  FinalFormat final_format = FinalFormat::hex;
  std::string resume_dir;  // --resume DIR (command line only)
  // [diagnostics]
  std::int64_t diag_every = 0;
  // [domain], [gravity], [material] or [material.NAME]
  Domain domain;  // the cell as given; a running Simulation's is the cell now (it deforms with cell.rate_*)
  bool cell_flow_start = true;                              // cell.flow_start
  double cell_stress_xx = 0.0, cell_stress_yy = 0.0;        // cell.stress_xx, stress_yy (0: no target)
  double cell_servo_gain = 0.0, cell_servo_max_rate = 1.0;  // cell.servo_gain, servo_max_rate
  // A length of the cell held at a target stress by the servo; the cell deforms (a rate or a target).
  bool cell_servo() const { return cell_stress_xx > 0.0 || cell_stress_yy > 0.0; }
  bool cell_deforms() const { return domain.moving || cell_servo(); }
  Vec2 gravity;
  double thickness = 1.0;           // every material's (the thickness stresses are per)
  std::vector<Material> materials;  // one ([material]) or several ([material.NAME], ordered by name)
  // [contact] and law blocks: the selected laws' keywords (physics/LawRegistry) and their parameters
  std::string normal_law, tangential_law, rolling_law;
  ContactParamTable params;
  // [bonds]: bonds are created at set-up (any key of [bonds] or a pair block [bonds.A.B] given) between discs whose
  // gap is at most bond_gap x the smaller radius; their parameters are in params' bond fields
  bool bonds = false;
  double bond_gap = 0.0;
  std::string bond_file;  // bonds.file: the pairs to bond ("" : every pair within bond_gap)
  // [neighbour]
  double skin = 0.0;  // 0: a quarter of the mean radius
  // [parallel]
  std::string partitioner;  // a name of core/Partitioners.hpp
  std::int64_t balance_every = 0;
  double balance_threshold = 0.0;
  bool force_balance = false;
  std::int64_t check_every = 0;
  // [walls]
  WallKeys wall_keys;
  WallSet walls;
  std::vector<std::string> box_walls;
  double servo_gain = 0.0, servo_max_speed = 0.0;
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
