#include "core/SceneTypes.hpp"

namespace rondel {

// The rows, each defined in its builder's file.
extern const SceneType kLatticeSquareScene, kLatticeHexScene, kRandomScene, kRandomTilesScene, kCsvScene, kFileScene;

namespace {
const SceneType* const kSceneTypes[] = {&kLatticeSquareScene, &kLatticeHexScene, &kRandomScene,
                                        &kRandomTilesScene,   &kCsvScene,        &kFileScene};
}  // namespace

std::span<const SceneType* const> scene_types() { return kSceneTypes; }

const SceneType* find_scene_type(const std::string& name) {
  for (const SceneType* t : kSceneTypes)
    if (name == t->name) return t;
  return nullptr;
}

}  // namespace rondel
