// scene.type = csv: the discs of scene.file, rows 'id,x,y,radius[,vx,vy,omega][,material]' (decimal or C99
// hexadecimal floats, as final.csv writes them; '#' comments; one header line), optionally replicated
// scene.replicate_x x scene.replicate_y times over the periodic box and then numbered in rows.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/DiscStore.hpp"
#include "core/Errors.hpp"
#include "core/MemoryLimit.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace {

void check_csv(SceneConfig& s) {
  if (s.file.empty()) throw ConfigError("missing required key 'scene.file' (scene.type = csv)");
  scene::check_numbering_placement(s);
}

std::string csv_keys(const SceneConfig& s) {
  return "the discs of scene.file '" + s.file + "', scene.replicate_x, scene.replicate_y";
}
std::string file_radius(const SceneConfig& s) { return "the radii of scene.file '" + s.file + "'"; }

// The numbers of one CSV row (file, line): an integer id in [0, 2^53), a finite position, a finite radius
// > 0, a finite velocity below the speed of light and a finite angular velocity.
void check_row(const std::string& file, std::size_t lineno, const std::vector<std::string>& tokens,
               const std::vector<double>& v) {
  static const char* const kColumns[7] = {"id", "x", "y", "radius", "vx", "vy", "omega"};
  auto refuse = [&](std::size_t col, const std::string& allowed) {
    throw InputError("scene.file '" + file + "' line " + std::to_string(lineno) + ": " + kColumns[col] + " = '" +
                     tokens[col] + "' is not allowed: " + allowed);
  };
  if (!(v[0] >= 0.0 && v[0] < static_cast<double>(kMaxGid) && v[0] == std::floor(v[0])))
    refuse(0, "an integer from 0 to 2^53 - 1");
  for (std::size_t col : {1, 2})
    if (!std::isfinite(v[col])) refuse(col, "a finite number");
  if (!(v[3] > 0.0 && std::isfinite(v[3]))) refuse(3, "radius must be > 0 and finite");
  for (std::size_t col = 4; col < v.size(); ++col)
    if (!std::isfinite(v[col]) || (col < 6 && std::fabs(v[col]) > config::kLightSpeed))
      refuse(col, col < 6 ? "a finite speed below the speed of light" : "a finite number");
}

// One data row as a disc (its tokens, a material name already taken off).
SceneDisc row_disc(const SceneConfig& s, std::size_t lineno, const std::vector<std::string>& tokens,
                   const std::vector<double>& v, const std::string& material) {
  check_row(s.file, lineno, tokens, v);
  SceneDisc d{static_cast<std::int64_t>(v[0]), {v[1], v[2]}, v[3], s.velocity, s.omega};
  const std::string where = "scene.file '" + s.file + "' line " + std::to_string(lineno);
  if (!material.empty()) {
    const auto it = std::find(s.material_names.begin(), s.material_names.end(), material);
    if (it == s.material_names.end())
      throw InputError(where + ": material '" + material + "' is not defined ([material.NAME])");
    d.material = static_cast<int>(it - s.material_names.begin());
  }
  if (v.size() == 7) d.v += Vec2{v[4], v[5]}, d.omega += v[6];
  if (!std::isfinite(d.v.x) || !std::isfinite(d.v.y) || !std::isfinite(d.omega))
    throw InputError(where + ": the velocity plus scene.vx, scene.vy, scene.omega is not finite");
  return d;
}

std::vector<SceneDisc> read_rows(const SceneConfig& s, const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("scene.file '" + s.file + "' cannot be read");
  std::vector<SceneDisc> base;
  std::string line;
  std::size_t lineno = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty() || line[0] == '#') continue;
    // strtod reads decimal and hexadecimal floats (final.csv is written in hexadecimal, bit-exact).
    std::replace(line.begin(), line.end(), ',', ' ');
    std::vector<std::string> tokens = config::split_words(line);
    std::string material;  // a last column after radius or omega: the material's name
    if (tokens.size() == 5 || tokens.size() == 8) material = tokens.back(), tokens.pop_back();
    std::vector<double> v;
    bool numeric = true;
    for (const std::string& tok : tokens) {
      char* end = nullptr;
      v.push_back(std::strtod(tok.c_str(), &end));
      if (end != tok.c_str() + tok.size()) numeric = false;
    }
    if (!numeric && base.empty() && !header_seen) {  // one header line before the data
      header_seen = true;
      continue;
    }
    if (!numeric || (v.size() != 4 && v.size() != 7))
      throw InputError("scene.file '" + s.file + "' line " + std::to_string(lineno) +
                       ": expected 'id,x,y,radius' or 'id,x,y,radius,vx,vy,omega', each optionally with a last "
                       "column material");
    base.push_back(row_disc(s, lineno, tokens, v, material));
  }
  return base;
}

// The copies, numbered anew in rows across the whole box: numbered one after the other, every row of the file
// would have a seam whose partners lay a whole copy of ids away.
std::vector<SceneDisc> replicate(const SceneConfig& s, const Domain& domain, const std::vector<SceneDisc>& base) {
  const double copies = static_cast<double>(s.replicate_x) * s.replicate_y;
  check_memory(static_cast<double>(base.size()) * copies, 0.0, 0.0,
               "scene.replicate_x x scene.replicate_y copies of the " + std::to_string(base.size()) + " discs of '" +
                   s.file + "'");
  const double px = domain.length_x() / s.replicate_x, py = domain.length_y() / s.replicate_y;
  std::vector<std::int64_t> ids(base.size());
  for (std::size_t k = 0; k < base.size(); ++k) ids[k] = base[k].gid;
  std::sort(ids.begin(), ids.end());
  const auto twice = std::adjacent_find(ids.begin(), ids.end());
  if (twice != ids.end())
    throw InputError("scene.file '" + s.file + "': disc id " + std::to_string(*twice) + " appears twice");
  std::vector<SceneDisc> out;
  out.reserve(base.size() * static_cast<std::size_t>(s.replicate_x) * static_cast<std::size_t>(s.replicate_y));
  for (int cy = 0; cy < s.replicate_y; ++cy)
    for (int cx = 0; cx < s.replicate_x; ++cx)
      for (auto d : base) {
        d.x += Vec2{cx * px, cy * py};
        out.push_back(d);
      }
  scene::number_in_rows(out, domain.ylo);
  return out;
}

std::vector<SceneDisc> csv(const SceneInputs& in) {
  const SceneConfig& s = in.scene;
  std::vector<SceneDisc> base = read_rows(s, scene::resolve(s.file, in.config_dir));
  if (s.replicate_x == 1 && s.replicate_y == 1) return base;
  return replicate(s, in.domain, base);
}

}  // namespace

extern const SceneType kCsvScene{"csv",       "the discs of scene.file, a CSV file", check_csv, csv_keys,
                                 file_radius, SceneType::Source::csv_file,           false,     csv};

}  // namespace rondel
