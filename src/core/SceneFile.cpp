// scene.type = file: the discs of a Rondel file (a checkpoint or snapshot; a directory: its newest complete
// checkpoint), with their materials; box walls take their positions from the file (a prepared sample keeps its
// box). History, step, time and strains start afresh: a new test stage. The composition root reads the file
// (SceneFileReader).
#include "core/ConfigRead.hpp"
#include "core/Errors.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace {

void check_file(SceneConfig& s) {
  if (s.file.empty())
    throw ConfigError("missing required key 'scene.file' (scene.type = file: a checkpoint or snapshot)");
  scene::check_numbering_placement(s);
}

std::string file_keys(const SceneConfig& s) { return "the discs of scene.file '" + s.file + "'"; }
std::string file_radius(const SceneConfig& s) { return "the radii of scene.file '" + s.file + "'"; }

std::vector<SceneDisc> from_file(const SceneInputs& in) {
  if (!in.files) throw InputError("scene.type = file: this program reads no Rondel files");
  return in.files->discs(in.scene.file);
}

}  // namespace

extern const SceneType kFileScene{"file",      "the discs of a Rondel checkpoint or snapshot (scene.file)",
                                  check_file,  file_keys,
                                  file_radius, SceneType::Source::state_file,
                                  false,       from_file};

}  // namespace rondel
