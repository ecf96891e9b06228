#include "core/SceneBuilder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/Errors.hpp"
#include "core/MemoryLimit.hpp"

namespace rondel {

std::uint64_t SceneRandom::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

namespace {

// The mean R^2 of the discs of material slot k (scene.material_by = area turns area fractions into numbers).
double mean_square_radius(const SceneConfig& s, std::size_t k) {
  if (s.material_radius_min.empty()) return 1.0;  // one radius law for every material: the areas cancel
  const double a = s.material_radius_min[k], b = s.material_radius_max[k];
  return s.distribution == "uniform_area" ? 0.5 * (a * a + b * b) : (a * a + a * b + b * b) / 3.0;
}

// The material slot (index into scene.materials) of each of n discs: exact counts from the fractions
// (largest remainder, ties to the lower slot), in an order shuffled by the scene's seed. Its own generator:
// the positions and radii draw the same numbers with or without materials.
std::vector<std::size_t> material_slots(const SceneConfig& s, std::size_t n) {
  const std::size_t m = s.materials.size();
  if (m == 0) return std::vector<std::size_t>(n, 0);
  std::vector<double> w(m);
  double total = 0.0;
  for (std::size_t k = 0; k < m; ++k)
    total += w[k] =
        s.material_by == "area" ? s.material_fractions[k] / mean_square_radius(s, k) : s.material_fractions[k];
  std::vector<std::size_t> count(m);
  std::vector<std::pair<double, std::size_t>> remainder;
  std::size_t given = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const double exact = static_cast<double>(n) * w[k] / total;
    count[k] = static_cast<std::size_t>(std::floor(exact));
    given += count[k];
    remainder.emplace_back(-(exact - std::floor(exact)), k);
  }
  std::sort(remainder.begin(), remainder.end());
  for (std::size_t r = 0; given < n; ++r, ++given) ++count[remainder[r % m].second];
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < m; ++k) out.insert(out.end(), count[k], k);
  SceneRandom rng(s.seed ^ 0x6d6174657269616cULL);  // "material"
  for (std::size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[rng.next() % i]);
  return out;
}

int slot_material(const SceneConfig& s, std::size_t slot) { return s.materials.empty() ? 0 : s.materials[slot]; }

std::vector<SceneDisc> lattice(const SceneConfig& s, const Domain& domain, bool hex) {
  check_memory(static_cast<double>(s.nx) * s.ny, 0.0, 0.0, "scene.nx x scene.ny");
  std::vector<SceneDisc> out;
  const double row = hex ? s.spacing * std::sqrt(3.0) / 2.0 : s.spacing;
  // The corners of the lattice (the first disc, the farthest row and column, the half shift of hex rows).
  const double far_x = s.x0 + (s.nx - 1) * s.spacing + (hex && s.ny > 1 ? 0.5 * s.spacing : 0.0),
               far_y = s.y0 + (s.ny - 1) * row;
  const bool inside_x = domain.periodic_x || (s.x0 >= domain.xlo && far_x <= domain.xhi);
  const bool inside_y = domain.periodic_y || (s.y0 >= domain.ylo && far_y <= domain.yhi);
  if (!std::isfinite(far_x) || !std::isfinite(far_y) || !inside_x || !inside_y) {
    std::ostringstream m;
    m << "keys 'scene.nx', 'scene.ny', 'scene.spacing' (" << s.spacing << "; 0: 2 x scene.radius), 'scene.x0', "
      << "'scene.y0': the lattice spans (" << s.x0 << ", " << s.y0 << ") to (" << far_x << ", " << far_y
      << "), outside the domain (domain.xlo, domain.xhi, domain.ylo, domain.yhi) [" << domain.xlo << ", " << domain.xhi
      << "] x [" << domain.ylo << ", " << domain.yhi << "]";
    throw InputError(m.str());
  }
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const double shift = (hex && (j % 2 == 1)) ? 0.5 * s.spacing : 0.0;
      out.push_back({static_cast<std::int64_t>(out.size()),
                     {s.x0 + i * s.spacing + shift, s.y0 + j * row},
                     s.radius,
                     s.velocity,
                     s.omega});
    }
  const auto slots = material_slots(s, out.size());
  for (std::size_t k = 0; k < out.size(); ++k) out[k].material = slot_material(s, slots[k]);
  return out;
}

// A radius, and its material: that of the slot (its own radius range when scene.material_radius_min is
// given), or of the size drawn (scene.size_materials).
std::pair<double, int> draw_radius(const SceneConfig& s, std::size_t slot, SceneRandom& rng) {
  const double u = rng.uniform();
  const bool own = !s.material_radius_min.empty();
  const double lo = own ? s.material_radius_min[slot] : s.radius_min,
               hi = own ? s.material_radius_max[slot] : s.radius_max;
  if (s.distribution == "uniform_radius") return {lo + u * (hi - lo), slot_material(s, slot)};
  if (s.distribution == "uniform_area") return {std::sqrt(lo * lo + u * (hi * hi - lo * lo)), slot_material(s, slot)};
  auto size = [&s](std::size_t k) {
    return std::pair<double, int>{s.sizes[k], s.size_materials.empty() ? 0 : s.size_materials[k]};
  };
  double acc = 0.0;
  for (std::size_t k = 0; k < s.sizes.size(); ++k) {
    acc += s.fractions[k];
    if (u < acc) return size(k);
  }
  return size(s.sizes.size() - 1);
}

// Numbers the discs 0, 1, ... in rows of height 2 R_max (R_max their largest radius) from `ylo` up, by x within
// a row, ties in their present order. The kernel reads the discs in id order (docs/design.md section 5): ids
// that follow space keep a disc's partners a row of ids away, so its reads stream (docs/benchmarks.md, "The
// order of the ids").
void number_in_rows(std::vector<SceneDisc>& discs, double ylo) {
  double R_max = 0.0;
  for (const auto& d : discs) R_max = std::max(R_max, d.radius);
  const double row_height = 2.0 * R_max;
  std::stable_sort(discs.begin(), discs.end(), [ylo, row_height](const SceneDisc& a, const SceneDisc& b) {
    const double ra = std::floor((a.x.y - ylo) / row_height), rb = std::floor((b.x.y - ylo) / row_height);
    return ra != rb ? ra < rb : a.x.x < b.x.x;
  });
  for (std::size_t k = 0; k < discs.size(); ++k) discs[k].gid = static_cast<std::int64_t>(k);
}

// Random sequential addition, largest discs first, with a cell grid for the overlap checks.
std::vector<SceneDisc> random_packing(const SceneConfig& s, const Domain& domain) {
  check_memory(static_cast<double>(s.count), 0.0, 0.0, "scene.count = " + std::to_string(s.count));
  SceneRandom rng(s.seed);
  const auto slots = material_slots(s, static_cast<std::size_t>(s.count));
  std::vector<std::pair<double, int>> radii(static_cast<std::size_t>(s.count));
  for (std::size_t k = 0; k < radii.size(); ++k) radii[k] = draw_radius(s, slots[k], rng);
  // Largest first; equal radii by material (a fixed order for a fixed seed).
  std::sort(radii.begin(), radii.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  const double xlo = s.region[0], xhi = s.region[1], ylo = s.region[2], yhi = s.region[3];
  const double r_max = radii.front().first;
  if (xhi - xlo < 2 * r_max || yhi - ylo < 2 * r_max)
    throw InputError(
        "scene.region (empty: walls.box_region, else the domain) is smaller than the largest disc "
        "(diameter " +
        std::to_string(2 * r_max).substr(0, 12) + " m; scene.radius_max, scene.sizes or scene.material_radius_max)");
  // Cells of side >= the largest diameter, at most about 4 per disc (the placement does not depend on the
  // cells: they only find the candidates; a region far larger than the discs gets larger cells).
  const double cell = 2.0 * r_max, cap = 4.0 * static_cast<double>(radii.size()) + 64.0;
  double fx = std::clamp(std::floor((xhi - xlo) / cell), 1.0, cap),
         fy = std::clamp(std::floor((yhi - ylo) / cell), 1.0, cap);
  while (fx * fy > cap) {
    double& larger = fx >= fy ? fx : fy;
    larger = std::max(1.0, std::floor(0.5 * larger));
  }
  const int nx = static_cast<int>(fx), ny = static_cast<int>(fy);
  const double cx = (xhi - xlo) / nx, cy = (yhi - ylo) / ny;
  std::vector<std::vector<std::size_t>> grid(static_cast<std::size_t>(nx) * ny);
  std::vector<SceneDisc> out;
  out.reserve(radii.size());
  for (const auto& [R, material] : radii) {
    bool placed = false;
    for (std::int64_t attempt = 0; attempt < s.max_attempts && !placed; ++attempt) {
      const Vec2 x{xlo + R + rng.uniform() * (xhi - xlo - 2 * R), ylo + R + rng.uniform() * (yhi - ylo - 2 * R)};
      const int ix = std::min(nx - 1, static_cast<int>((x.x - xlo) / cx));
      const int iy = std::min(ny - 1, static_cast<int>((x.y - ylo) / cy));
      bool free = true;
      for (int dy = -1; dy <= 1 && free; ++dy)
        for (int dx = -1; dx <= 1 && free; ++dx) {
          int gx = ix + dx, gy = iy + dy;
          if (domain.periodic_x) gx = (gx + nx) % nx;
          if (domain.periodic_y) gy = (gy + ny) % ny;
          if (gx < 0 || gx >= nx || gy < 0 || gy >= ny) continue;
          for (std::size_t k : grid[static_cast<std::size_t>(gy) * nx + gx]) {
            const Vec2 d = domain.separation(x, out[k].x);
            const double reach = R + out[k].radius;
            if (dot(d, d) < reach * reach) {
              free = false;
              break;
            }
          }
        }
      if (!free) continue;
      grid[static_cast<std::size_t>(iy) * nx + ix].push_back(out.size());
      out.push_back({static_cast<std::int64_t>(out.size()), x, R, s.velocity, s.omega, material});
      placed = true;
    }
    if (!placed) {
      std::ostringstream m;
      m << "scene.count = " << s.count << ": only " << out.size()
        << " discs fit in scene.region without overlap after scene.max_attempts = " << s.max_attempts
        << " tries each; lower scene.count or the radii, or enlarge scene.region";
      throw InputError(m.str());
    }
  }
  if (s.numbering == "rows") number_in_rows(out, ylo);
  return out;
}

std::string resolve(const std::string& file, const std::string& config_dir) {
  namespace fs = std::filesystem;
  if (fs::path(file).is_absolute() || fs::exists(file) || config_dir.empty()) return file;
  const fs::path alt = fs::path(config_dir) / file;
  return fs::exists(alt) ? alt.string() : file;
}

// The numbers of one CSV row (file, line): an integer id in [0, 2^53), a finite position, a finite radius
// > 0, a finite velocity below the speed of light and a finite angular velocity.
void check_row(const std::string& file, std::size_t lineno, const std::vector<std::string>& tokens,
               const std::vector<double>& v) {
  static const char* const kColumns[7] = {"id", "x", "y", "radius", "vx", "vy", "omega"};
  auto refuse = [&](std::size_t col, const std::string& allowed) {
    throw InputError("scene.file '" + file + "' line " + std::to_string(lineno) + ": " + kColumns[col] + " = '" +
                     tokens[col] + "' is not allowed: " + allowed);
  };
  if (!(v[0] >= 0.0 && v[0] < 0x1p53 && v[0] == std::floor(v[0]))) refuse(0, "an integer from 0 to 2^53 - 1");
  for (std::size_t col : {1, 2})
    if (!std::isfinite(v[col])) refuse(col, "a finite number");
  if (!(v[3] > 0.0 && std::isfinite(v[3]))) refuse(3, "radius must be > 0 and finite");
  for (std::size_t col = 4; col < v.size(); ++col)
    if (!std::isfinite(v[col]) || (col < 6 && std::fabs(v[col]) > 299792458.0))
      refuse(col, col < 6 ? "a finite speed below the speed of light" : "a finite number");
}

std::vector<SceneDisc> csv(const SceneConfig& s, const Domain& domain, const std::string& config_dir) {
  const std::string path = resolve(s.file, config_dir);
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
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string tok; fields >> tok;) tokens.push_back(tok);
    std::string material;  // a last column after radius or omega: the material's name
    if (tokens.size() == 5 || tokens.size() == 8) material = tokens.back(), tokens.pop_back();
    std::vector<double> v;
    bool numeric = true;
    for (const std::string& tok : tokens) {
      char* end = nullptr;
      const double x = std::strtod(tok.c_str(), &end);
      if (end != tok.c_str() + tok.size()) numeric = false;
      v.push_back(x);
    }
    if (!numeric && base.empty() && !header_seen) {  // one header line before the data
      header_seen = true;
      continue;
    }
    if (!numeric || (v.size() != 4 && v.size() != 7))
      throw InputError("scene.file '" + s.file + "' line " + std::to_string(lineno) +
                       ": expected 'id,x,y,radius' or 'id,x,y,radius,vx,vy,omega', each optionally with a last "
                       "column material");
    check_row(s.file, lineno, tokens, v);
    SceneDisc d{static_cast<std::int64_t>(v[0]), {v[1], v[2]}, v[3], s.velocity, s.omega};
    if (!material.empty()) {
      const auto it = std::find(s.material_names.begin(), s.material_names.end(), material);
      if (it == s.material_names.end())
        throw InputError("scene.file '" + s.file + "' line " + std::to_string(lineno) + ": material '" + material +
                         "' is not defined ([material.NAME])");
      d.material = static_cast<int>(it - s.material_names.begin());
    }
    if (v.size() == 7) d.v += Vec2{v[4], v[5]}, d.omega += v[6];
    if (!std::isfinite(d.v.x) || !std::isfinite(d.v.y) || !std::isfinite(d.omega))
      throw InputError("scene.file '" + s.file + "' line " + std::to_string(lineno) +
                       ": the velocity plus scene.vx, scene.vy, scene.omega is not finite");
    base.push_back(d);
  }
  if (s.replicate_x == 1 && s.replicate_y == 1) return base;
  const double copies = static_cast<double>(s.replicate_x) * s.replicate_y;
  check_memory(static_cast<double>(base.size()) * copies, 0.0, 0.0,
               "scene.replicate_x x scene.replicate_y copies of the " + std::to_string(base.size()) + " discs of '" +
                   s.file + "'");
  const double px = domain.length_x() / s.replicate_x, py = domain.length_y() / s.replicate_y;
  // The copies, numbered anew in rows across the whole box: numbered one after the other, every row of the
  // file would have a seam whose partners lay a whole copy of ids away.
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
  number_in_rows(out, domain.ylo);
  return out;
}

}  // namespace

std::vector<SceneDisc> build_scene(const SceneConfig& scene, const Domain& domain, const std::string& config_dir) {
  std::vector<SceneDisc> discs;
  if (scene.type == "lattice_square")
    discs = lattice(scene, domain, false);
  else if (scene.type == "lattice_hex")
    discs = lattice(scene, domain, true);
  else if (scene.type == "random")
    discs = random_packing(scene, domain);
  else
    discs = csv(scene, domain, config_dir);
  std::sort(discs.begin(), discs.end(), [](const SceneDisc& a, const SceneDisc& b) { return a.gid < b.gid; });
  for (std::size_t k = 1; k < discs.size(); ++k)
    if (discs[k].gid == discs[k - 1].gid)
      throw InputError("scene: disc id " + std::to_string(discs[k].gid) + " appears twice");
  return discs;
}

}  // namespace rondel
