// [scene]: the initial discs (a lattice, a random packing, a CSV file or a Rondel file).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/ConfigRead.hpp"

namespace rondel::config {

namespace {

// The keys the scene's type needs, with their ranges.
void check_scene_type(const Reader& r, SceneConfig& s) {
  if (s.type == "lattice_square" || s.type == "lattice_hex") {
    check(s.nx > 0, "scene.nx", "must be > 0 for a lattice", std::to_string(s.nx));
    check(s.ny > 0, "scene.ny", "must be > 0 for a lattice", std::to_string(s.ny));
    positive(r, "scene.radius");
    if (s.spacing == 0.0) s.spacing = 2.0 * s.radius;
    check(s.spacing > 0.0, "scene.spacing", "must be > 0 (or 0 for 2 x radius)", num(s.spacing));
  } else if (s.type == "random") {
    check(s.count > 0, "scene.count", "must be > 0 for a random scene", std::to_string(s.count));
    check(s.max_attempts > 0, "scene.max_attempts", "must be > 0", std::to_string(s.max_attempts));
    const bool own_ranges = !r.get<std::string>("scene.material_radius_min").empty();
    if ((s.distribution == "uniform_radius" || s.distribution == "uniform_area") && own_ranges) {
      // each material's own range (read_scene_materials)
    } else if (s.distribution == "uniform_radius" || s.distribution == "uniform_area") {
      positive(r, "scene.radius_min");
      check(s.radius_max >= s.radius_min, "scene.radius_max", ">= scene.radius_min", num(s.radius_max));
    } else if (s.distribution == "list") {
      check(!s.sizes.empty() && s.sizes.size() == s.fractions.size(), "scene.fractions",
            "one fraction per size in scene.sizes",
            std::to_string(s.fractions.size()) + " fractions for " + std::to_string(s.sizes.size()) + " sizes");
      double sum = 0.0;
      for (double v : s.sizes) check(v > 0.0, "scene.sizes", "radii must be > 0", num(v));
      for (double f : s.fractions) check(f >= 0.0, "scene.fractions", "fractions must be >= 0", num(f)), sum += f;
      check(std::fabs(sum - 1.0) < 1e-9, "scene.fractions", "fractions must sum to 1", num(sum));
    } else {
      throw ConfigError("key 'scene.distribution' = " + s.distribution +
                        " is not allowed: uniform_radius | uniform_area | list");
    }
    if (s.numbering != "placement" && s.numbering != "rows")
      throw ConfigError("key 'scene.numbering' = " + s.numbering + " is not allowed: placement | rows");
  } else if (s.type == "file") {
    if (s.file.empty())
      throw ConfigError("missing required key 'scene.file' (scene.type = file: a checkpoint or snapshot)");
  } else if (s.type == "csv") {
    if (s.file.empty()) throw ConfigError("missing required key 'scene.file' (scene.type = csv)");
    check(s.replicate_x >= 1, "scene.replicate_x", "must be >= 1", std::to_string(s.replicate_x));
    check(s.replicate_y >= 1, "scene.replicate_y", "must be >= 1", std::to_string(s.replicate_y));
  } else {
    throw ConfigError("key 'scene.type' = " + s.type +
                      " is not allowed: lattice_square | lattice_hex | random | csv | file");
  }
  check(s.type == "random" || s.numbering == "placement", "scene.numbering",
        "only with scene.type = random (lattices and replicated copies are numbered in rows, a csv file keeps its "
        "ids)",
        s.numbering + " with scene.type = " + s.type);
}

}  // namespace

void read_scene(const Reader& r, Config& c) {
  SceneConfig& s = c.scene;
  if (!r.vm.count("scene.type"))
    throw ConfigError("missing required key 'scene.type' (lattice_square | lattice_hex | random | csv)");
  s.type = r.get<std::string>("scene.type");
  s.nx = r.get<int>("scene.nx");
  s.ny = r.get<int>("scene.ny");
  s.radius = r.get<double>("scene.radius");
  s.spacing = r.get<double>("scene.spacing");
  s.x0 = r.get<double>("scene.x0");
  s.y0 = r.get<double>("scene.y0");
  s.count = r.get<std::int64_t>("scene.count");
  s.distribution = r.get<std::string>("scene.distribution");
  s.radius_min = r.get<double>("scene.radius_min");
  s.radius_max = r.get<double>("scene.radius_max");
  s.sizes = numbers(r.get<std::string>("scene.sizes"), "scene.sizes");
  s.fractions = numbers(r.get<std::string>("scene.fractions"), "scene.fractions");
  s.seed = static_cast<std::uint64_t>(r.get<std::int64_t>("scene.seed"));  // >= 0 (validate_values)
  s.max_attempts = r.get<std::int64_t>("scene.max_attempts");
  s.numbering = r.get<std::string>("scene.numbering");
  s.file = r.get<std::string>("scene.file");
  s.replicate_x = r.get<int>("scene.replicate_x");
  s.replicate_y = r.get<int>("scene.replicate_y");
  s.velocity = {r.get<double>("scene.vx"), r.get<double>("scene.vy")};
  s.omega = r.get<double>("scene.omega");
  s.max_initial_overlap = r.get<double>("scene.max_initial_overlap");
  non_negative(s.max_initial_overlap, "scene.max_initial_overlap");
  // The default region is the box of the walls (walls.box_region), else the domain.
  auto region = numbers(r.get<std::string>("scene.region"), "scene.region");
  if (region.empty()) region = numbers(r.get<std::string>("walls.box_region"), "walls.box_region");
  const Domain& d = c.domain;
  const double box[4] = {d.xlo, d.xhi, d.ylo, d.yhi};
  if (region.empty())
    std::copy(box, box + 4, s.region);
  else if (region.size() == 4 && region[0] < region[1] && region[2] < region[3])
    std::copy(region.begin(), region.end(), s.region);
  else
    throw ConfigError("key 'scene.region' must be 'xlo xhi ylo yhi' with xlo < xhi and ylo < yhi");

  check_scene_type(r, s);
}

namespace {

std::vector<int> material_list(const Config& c, const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::vector<int> out;
  for (std::string name; in >> name;) {
    const int i = material_index(c.materials, name);
    if (i < 0) throw ConfigError("key '" + key + "' names the material '" + name + "', which is not defined");
    out.push_back(i);
  }
  return out;
}

void check_fractions(const std::vector<double>& f, std::size_t n, const std::string& key, const std::string& of) {
  check(f.size() == n, key, "one fraction per name in " + of, std::to_string(f.size()) + " for " + std::to_string(n));
  double sum = 0.0;
  for (double v : f) check(v >= 0.0, key, "fractions must be >= 0", num(v)), sum += v;
  check(std::fabs(sum - 1.0) < 1e-9, key, "fractions must sum to 1", num(sum));
}

}  // namespace

void read_scene_materials(const Reader& r, Config& c) {
  SceneConfig& s = c.scene;
  for (const Material& m : c.materials) s.material_names.push_back(m.name);
  s.materials = material_list(c, r.get<std::string>("scene.materials"), "scene.materials");
  s.material_fractions = numbers(r.get<std::string>("scene.material_fractions"), "scene.material_fractions");
  s.material_by = r.get<std::string>("scene.material_by");
  check(s.material_by == "number" || s.material_by == "area", "scene.material_by", "number | area", s.material_by);
  s.material_radius_min = numbers(r.get<std::string>("scene.material_radius_min"), "scene.material_radius_min");
  s.material_radius_max = numbers(r.get<std::string>("scene.material_radius_max"), "scene.material_radius_max");
  s.size_materials = material_list(c, r.get<std::string>("scene.size_materials"), "scene.size_materials");
  const bool lattice_or_random = s.type == "lattice_square" || s.type == "lattice_hex" || s.type == "random";
  if (!s.materials.empty()) {
    // A file scene keeps the materials its discs have in the file: the keys are left unused.
    check(lattice_or_random || s.type == "file", "scene.materials",
          "a lattice or random scene (csv: a material column)", s.type);
    if (s.materials.size() > 1 || !s.material_fractions.empty())
      check_fractions(s.material_fractions, s.materials.size(), "scene.material_fractions", "scene.materials");
    if (s.material_fractions.empty()) s.material_fractions = {1.0};
  } else if (!s.material_fractions.empty()) {
    throw ConfigError("key 'scene.material_fractions' needs scene.materials");
  }
  const std::size_t ranges = s.material_radius_min.size() + s.material_radius_max.size();
  if (ranges > 0) {
    check(s.type == "random" && s.distribution != "list", "scene.material_radius_min' / 'scene.material_radius_max",
          "a random scene with uniform_radius or uniform_area", s.type + " / " + s.distribution);
    check(s.material_radius_min.size() == s.materials.size() && s.material_radius_max.size() == s.materials.size(),
          "scene.material_radius_min' / 'scene.material_radius_max",
          "one smallest and one largest radius per name in scene.materials",
          std::to_string(s.material_radius_min.size()) + " and " + std::to_string(s.material_radius_max.size()));
    for (std::size_t k = 0; k < s.materials.size(); ++k) {
      check(s.material_radius_min[k] > 0.0, "scene.material_radius_min", "must be > 0", num(s.material_radius_min[k]));
      check(s.material_radius_max[k] >= s.material_radius_min[k], "scene.material_radius_max",
            ">= scene.material_radius_min", num(s.material_radius_max[k]));
    }
  }
  if (!s.size_materials.empty()) {
    check(s.type == "random" && s.distribution == "list", "scene.size_materials", "a random scene with list",
          s.type + " / " + s.distribution);
    check(s.size_materials.size() == s.sizes.size(), "scene.size_materials", "one material per size in scene.sizes",
          std::to_string(s.size_materials.size()));
    check(s.materials.empty(), "scene.materials", "not with scene.size_materials (the sizes give the materials)",
          r.get<std::string>("scene.materials"));
  }
  // The discs glued to a rough wall may take a material of their own (walls.rough_materials).
  s.rough_materials.assign(4, -1);
  std::istringstream in(r.get<std::string>("walls.rough_materials"));
  static const char* kSides[4] = {"bottom", "left", "right", "top"};
  for (std::string spec; in >> spec;) {
    const auto colon = spec.find(':');
    int side = -1;
    for (int k = 0; k < 4; ++k)
      if (spec.substr(0, colon) == kSides[k]) side = k;
    if (colon == std::string::npos || side < 0)
      throw ConfigError("key 'walls.rough_materials': '" + spec + "' is not 'side:NAME' with a box side");
    s.rough_materials[static_cast<std::size_t>(side)] =
        material_list(c, spec.substr(colon + 1), "walls.rough_materials").at(0);
  }
}

}  // namespace rondel::config
