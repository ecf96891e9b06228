#pragma once
// The discs of a new scene, and what the scene builders share (core/SceneTypes.hpp lists the builders).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/Config.hpp"
#include "core/Vec2.hpp"

namespace rondel {

struct SceneDisc {
  std::int64_t gid;
  Vec2 x;
  double radius;
  Vec2 v;
  double omega;
  int material = 0;  // index into Config::materials
};

struct SceneInputs;

// Where a builder that finds its discs one at a time puts them (SceneType::cells): the set-up's disc store
// directly (Simulation::add_scene_discs), with no list of the rank's discs beside it (64 B a disc).
struct SceneSink {
  virtual ~SceneSink() = default;
  virtual void reserve(std::size_t n) = 0;  // the exact number of discs that follow
  virtual void add(const SceneDisc& d) = 0;
};

// The discs of the scene of `in.scene.type`, in ascending gid. Every rank builds the same list from the
// configuration alone (the random packing draws from its own seeded generator), so the scene does not depend on
// the rank count. Throws InputError naming the key or file when the scene cannot be built, or when two discs
// have one id.
std::vector<SceneDisc> build_scene(const SceneInputs& in);
// This rank's block of the scene when it is built in blocks (scene::in_blocks): the gids [N r / P, N (r + 1) / P)
// of its N discs, in ascending gid; the same discs as build_scene's.
std::vector<SceneDisc> build_scene_block(const SceneInputs& in, int rank, int ranks);

// A small, portable generator (splitmix64): the same numbers on every platform and compiler.
class SceneRandom {
 public:
  explicit SceneRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t state_;
};

namespace scene {

// The material slot (index into scene.materials) of each of n discs: exact counts from the fractions (largest
// remainder, ties to the lower slot), in an order shuffled by the scene's seed.
std::vector<std::size_t> material_slots(const SceneConfig& s, std::size_t n);
// The exact number of discs of each material slot among n (as material_slots counts them; {n} without materials).
std::vector<std::size_t> material_counts(const SceneConfig& s, std::size_t n);
// A bijection of [0, n) keyed by `key` (a Feistel network, cycle-walked into [0, n)): each element's image alone.
std::uint64_t keyed_permutation(std::uint64_t k, std::uint64_t n, std::uint64_t key);
// The material slot of disc k of n: the exact counts `counts` (material_counts) in the order of a permutation keyed
// by the scene's seed, computed for one disc alone (a lattice built in blocks).
std::size_t material_slot_of(const SceneConfig& s, const std::vector<std::size_t>& counts, std::uint64_t n,
                             std::uint64_t k);
// The material of a slot (0 without scene.materials).
int slot_material(const SceneConfig& s, std::size_t slot);
// Whether each rank holds a block of the scene, not the whole: a type with a block builder (a lattice), a Rondel
// file (each rank reads its block of the rows) or a CSV file (each rank its block of the bytes; replicated, its
// block of the copies' ids, scene_csv::replicated_block).
bool in_blocks(const SceneConfig& s);
// The radius of the discs of a scene built cell by cell (SceneType::by_cells), 0 when it is not.
double by_cells(const SceneInputs& in);
// Numbers the discs 0, 1, ... in rows of height 2 R_max from `ylo` up, by x within a row (docs/design.md section 5).
void number_in_rows(std::vector<SceneDisc>& discs, double ylo);
// scene.type may use the material scene.numbering = placement only (random: rows too).
void check_numbering_placement(const SceneConfig& s);
// "scene.file 'F'" resolved: as given when it exists, else next to the INI file.
std::string resolve(const std::string& file, const std::string& config_dir);

}  // namespace scene

}  // namespace rondel
