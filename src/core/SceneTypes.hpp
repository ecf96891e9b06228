#pragma once
// The scene builders' registry (docs/developing.md, "How to add a scene type"): one row per scene.type, each
// defined in its builder's own file (SceneLattice.cpp, ScenePacking.cpp, SceneCsv.cpp, SceneFile.cpp) and listed
// once in SceneTypes.cpp. The configuration reads scene.type against it (--help lists it), checks the keys the
// type needs with its row, and the set-up builds the discs with it; nothing else names a scene type.
#include <span>
#include <string>
#include <vector>

#include "core/CellGrid.hpp"
#include "core/Config.hpp"
#include "core/SceneBuilder.hpp"

namespace rondel {

// Reads a scene's file in blocks over the ranks: the discs of a Rondel file (a checkpoint or snapshot; a directory:
// its newest complete checkpoint) for scene.type = file, and of a CSV file for scene.type = csv. The composition root
// implements it (it needs HDF5 and MPI); core only calls it. Without one, a CSV file is read whole.
struct SceneFileReader {
  virtual ~SceneFileReader() = default;
  // This rank's block of the file's discs (collective: every rank calls it).
  virtual std::vector<SceneDisc> discs(const std::string& path) const = 0;
  // This rank's block of the discs of the CSV file `path` of scene `s` (core/SceneCsv.hpp), its ids checked distinct
  // over all the ranks (collective).
  virtual std::vector<SceneDisc> csv(const SceneConfig& s, const std::string& path) const = 0;
};

struct SceneInputs {
  const SceneConfig& scene;
  const Domain& domain;
  std::string config_dir;                  // a relative scene.file not found is looked up there (the INI's directory)
  const SceneFileReader* files = nullptr;  // scene.type = file, and csv read in blocks
};

struct SceneType {
  const char* name;  // its word for scene.type
  const char* help;  // for --help
  // The keys it needs and their rules, when the configuration is read (throws ConfigError naming the key).
  void (*check)(SceneConfig& scene);
  // The keys that place its discs, and those that set their radii, for the messages of the set-up checks.
  std::string (*placement_keys)(const SceneConfig& scene);
  std::string (*radius_keys)(const SceneConfig& scene);
  // Where the discs and their materials come from: the scene keys (scene.materials assigns them), a CSV file
  // (its material column; scene.materials is refused), or a Rondel file (its materials; scene.materials is left
  // unused, so that a stage may keep the keys of the stage before). From a file, the discs' velocities are the
  // file's plus scene.vx, scene.vy, scene.omega.
  enum class Source { keys, csv_file, state_file } source;
  // Its radii are drawn (scene.distribution): scene.material_radius_min/_max and scene.size_materials apply.
  bool draws_radii;
  std::vector<SceneDisc> (*build)(const SceneInputs& in);
  // A scene whose every disc follows from its gid alone (a lattice) also gives its disc count and the discs of the
  // gids [first, first + count): each rank builds its own block and nothing on a rank grows with the whole scene
  // (scene::in_blocks says when; docs/scaling.md, "Set-up"). nullptr: every rank builds the whole scene.
  std::int64_t (*total)(const SceneConfig& scene) = nullptr;
  std::vector<SceneDisc> (*block)(const SceneInputs& in, std::int64_t first, std::int64_t count) = nullptr;
  // A scene whose discs can be found cell by cell (a lattice inside an untilted domain, a random packing placed
  // tile by tile) gives its largest radius (0: it cannot here, nullptr: never), the number of its discs in a rectangle
  // of cells [x0, x1) x [y0, y1) of the decomposition's grid (the first map is weighted by them: exact for a lattice,
  // expected for a random packing) and the discs of a rank's cells in ascending gid, given to `out` one at a time
  // after their exact count, so that no disc moves to its owner and no list of them is made beside the store (a
  // random packing keeps the tiles it placed, 32 B a disc, until they are given) (Simulation::add_scene_discs; the
  // same discs as build's).
  double (*by_cells)(const SceneInputs& in) = nullptr;
  std::uint64_t (*rect_count)(const SceneInputs& in, const CellGrid& grid, int x0, int y0, int x1, int y1) = nullptr;
  void (*cells)(const SceneInputs& in, const CellGrid& grid, const std::vector<std::size_t>& cells,
                SceneSink& out) = nullptr;
  // A scene of several radii built cell by cell gives by_cells its largest radius and here the mean radius it
  // expects (the neighbour skin's default is a quarter of the mean), so that the grid of the first map is, but for
  // rounding, the grid of the discs' own range (nullptr: by_cells's radius, a scene of one radius).
  double (*mean_radius)(const SceneConfig& scene) = nullptr;
};

std::span<const SceneType* const> scene_types();
// The row named `name`; nullptr when none.
const SceneType* find_scene_type(const std::string& name);

}  // namespace rondel
