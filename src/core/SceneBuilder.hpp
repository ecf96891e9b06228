#pragma once
#include <cstdint>
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

// Builds the initial discs of a scene. Every rank builds the same list from the configuration alone (the
// random packing draws from its own seeded generator), so the scene does not depend on the rank count.
// Throws InputError naming the key or file when the scene cannot be built.
std::vector<SceneDisc> build_scene(const SceneConfig& scene, const Domain& domain, const std::string& config_dir);

// A small, portable generator (splitmix64): the same numbers on every platform and compiler.
class SceneRandom {
 public:
  explicit SceneRandom(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t state_;
};

}  // namespace rondel
