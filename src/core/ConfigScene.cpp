// [scene]: the rules across its keys (the rows of ConfigSchema.cpp fill the fields; the scene type's own rules
// are in its row of the scene registry, core/SceneTypes.hpp).
#include <algorithm>
#include <cmath>

#include "core/ConfigRead.hpp"
#include "core/SceneTypes.hpp"

namespace rondel::config {

void read_scene(Config& c) {
  SceneConfig& s = c.scene;
  // The default region is the box of the walls (walls.box_region), else the domain.
  const std::vector<double>& region = !s.region_given.empty() ? s.region_given : c.wall_keys.box_region;
  const Domain& d = c.domain;
  const double box[4] = {d.xlo, d.xhi, d.ylo, d.yhi};
  if (region.empty())
    std::copy(box, box + 4, s.region);
  else if (region.size() == 4 && region[0] < region[1] && region[2] < region[3])
    std::copy(region.begin(), region.end(), s.region);
  else
    throw ConfigError("key 'scene.region' must be 'xlo xhi ylo yhi' with xlo < xhi and ylo < yhi");
  s.type->check(s);
}

namespace {

std::vector<int> material_list(const Config& c, const std::vector<std::string>& names, const std::string& key) {
  std::vector<int> out;
  for (const std::string& name : names) {
    const int i = material_index(c.materials, name);
    if (i < 0) throw ConfigError("key '" + key + "' names the material '" + name + "', which is not defined");
    out.push_back(i);
  }
  return out;
}

void check_fractions(const std::vector<double>& f, std::size_t n, const std::string& key, const std::string& of) {
  check(f.size() == n, key, "one fraction per name in " + of, std::to_string(f.size()) + " for " + std::to_string(n));
  double sum = 0.0;
  for (double v : f) sum += v;
  check(std::fabs(sum - 1.0) < 1e-9, key, "fractions must sum to 1", num(sum));
}

// scene.material_radius_min / _max: one range per material of scene.materials, for uniform random radii.
void check_material_ranges(const SceneConfig& s) {
  const char* keys = "scene.material_radius_min' / 'scene.material_radius_max";
  check(s.type->draws_radii && s.distribution != Distribution::list, keys,
        "a random scene with uniform_radius or uniform_area", std::string(s.type->name));
  check(s.material_radius_min.size() == s.materials.size() && s.material_radius_max.size() == s.materials.size(), keys,
        "one smallest and one largest radius per name in scene.materials",
        std::to_string(s.material_radius_min.size()) + " and " + std::to_string(s.material_radius_max.size()));
  for (std::size_t k = 0; k < s.materials.size(); ++k)
    check(s.material_radius_max[k] >= s.material_radius_min[k], "scene.material_radius_max",
          ">= scene.material_radius_min", num(s.material_radius_max[k]));
}

// walls.rough_materials 'side:NAME ...': the discs glued to that rough wall take material NAME.
void read_rough_materials(Config& c) {
  SceneConfig& s = c.scene;
  s.rough_materials.assign(4, -1);
  for (const std::string& spec : c.wall_keys.rough_materials) {
    const auto colon = spec.find(':');
    const int side = box_side_index(spec.substr(0, colon));
    if (colon == std::string::npos || side < 0)
      throw ConfigError("key 'walls.rough_materials': '" + spec + "' is not 'side:NAME' with a box side");
    s.rough_materials[static_cast<std::size_t>(side)] =
        material_list(c, {spec.substr(colon + 1)}, "walls.rough_materials").at(0);
  }
}

}  // namespace

void read_scene_materials(Config& c) {
  SceneConfig& s = c.scene;
  for (const Material& m : c.materials) s.material_names.push_back(m.name);
  s.materials = material_list(c, s.material_words, "scene.materials");
  s.size_materials = material_list(c, s.size_material_words, "scene.size_materials");
  if (!s.materials.empty()) {
    // A file scene keeps the materials its discs have in the file: the keys are left unused.
    check(s.type->source != SceneType::Source::csv_file, "scene.materials",
          "a lattice or random scene (csv: a material column)", s.type->name);
    if (s.materials.size() > 1 || !s.material_fractions.empty())
      check_fractions(s.material_fractions, s.materials.size(), "scene.material_fractions", "scene.materials");
    if (s.material_fractions.empty()) s.material_fractions = {1.0};
  } else if (!s.material_fractions.empty()) {
    throw ConfigError("key 'scene.material_fractions' needs scene.materials");
  }
  if (!s.material_radius_min.empty() || !s.material_radius_max.empty()) check_material_ranges(s);
  if (!s.size_materials.empty()) {
    check(s.type->draws_radii && s.distribution == Distribution::list, "scene.size_materials",
          "a random scene with list", s.type->name);
    check(s.size_materials.size() == s.sizes.size(), "scene.size_materials", "one material per size in scene.sizes",
          std::to_string(s.size_materials.size()));
    check(s.materials.empty(), "scene.materials", "not with scene.size_materials (the sizes give the materials)",
          std::to_string(s.materials.size()) + " names");
  }
  read_rough_materials(c);
}

}  // namespace rondel::config
