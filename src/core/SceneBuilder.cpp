#include "core/SceneBuilder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/Errors.hpp"

namespace rondel {

std::uint64_t SceneRandom::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

namespace {

std::vector<SceneDisc> lattice(const SceneConfig& s, bool hex) {
  std::vector<SceneDisc> out;
  const double row = hex ? s.spacing * std::sqrt(3.0) / 2.0 : s.spacing;
  for (int j = 0; j < s.ny; ++j)
    for (int i = 0; i < s.nx; ++i) {
      const double shift = (hex && (j % 2 == 1)) ? 0.5 * s.spacing : 0.0;
      out.push_back({static_cast<std::int64_t>(out.size()),
                     {s.x0 + i * s.spacing + shift, s.y0 + j * row},
                     s.radius,
                     s.velocity,
                     s.omega});
    }
  return out;
}

double draw_radius(const SceneConfig& s, SceneRandom& rng) {
  const double u = rng.uniform();
  if (s.distribution == "uniform_radius") return s.radius_min + u * (s.radius_max - s.radius_min);
  if (s.distribution == "uniform_area")
    return std::sqrt(s.radius_min * s.radius_min + u * (s.radius_max * s.radius_max - s.radius_min * s.radius_min));
  double acc = 0.0;
  for (std::size_t k = 0; k < s.sizes.size(); ++k) {
    acc += s.fractions[k];
    if (u < acc) return s.sizes[k];
  }
  return s.sizes.back();
}

// Random sequential addition, largest discs first, with a cell grid for the overlap checks.
std::vector<SceneDisc> random_packing(const SceneConfig& s, const Domain& domain) {
  SceneRandom rng(s.seed);
  std::vector<double> radii(static_cast<std::size_t>(s.count));
  for (double& r : radii) r = draw_radius(s, rng);
  std::sort(radii.begin(), radii.end(), std::greater<>());
  const double xlo = s.region[0], xhi = s.region[1], ylo = s.region[2], yhi = s.region[3];
  const double r_max = radii.front();
  if (xhi - xlo < 2 * r_max || yhi - ylo < 2 * r_max)
    throw InputError("scene.region is smaller than the largest disc (diameter " + std::to_string(2 * r_max) + ")");
  const double cell = 2.0 * r_max;
  const int nx = std::max(1, static_cast<int>((xhi - xlo) / cell)),
            ny = std::max(1, static_cast<int>((yhi - ylo) / cell));
  const double cx = (xhi - xlo) / nx, cy = (yhi - ylo) / ny;
  std::vector<std::vector<std::size_t>> grid(static_cast<std::size_t>(nx) * ny);
  std::vector<SceneDisc> out;
  out.reserve(radii.size());
  for (double R : radii) {
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
      out.push_back({static_cast<std::int64_t>(out.size()), x, R, s.velocity, s.omega});
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
  return out;
}

std::string resolve(const std::string& file, const std::string& config_dir) {
  namespace fs = std::filesystem;
  if (fs::path(file).is_absolute() || fs::exists(file) || config_dir.empty()) return file;
  const fs::path alt = fs::path(config_dir) / file;
  return fs::exists(alt) ? alt.string() : file;
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
    std::vector<double> v;
    bool numeric = true;
    for (std::string tok; fields >> tok;) {
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
                       ": expected 'id,x,y,radius' or 'id,x,y,radius,vx,vy,omega'");
    SceneDisc d{static_cast<std::int64_t>(v[0]), {v[1], v[2]}, v[3], s.velocity, s.omega};
    if (v.size() == 7) d.v += Vec2{v[4], v[5]}, d.omega += v[6];
    if (!(d.radius > 0.0))
      throw InputError("scene.file '" + s.file + "' line " + std::to_string(lineno) + ": radius must be > 0");
    base.push_back(d);
  }
  if (s.replicate_x == 1 && s.replicate_y == 1) return base;
  std::int64_t id_span = 0;
  for (const auto& d : base) id_span = std::max(id_span, d.gid + 1);
  const double px = domain.length_x() / s.replicate_x, py = domain.length_y() / s.replicate_y;
  std::vector<SceneDisc> out;
  for (int cy = 0; cy < s.replicate_y; ++cy)
    for (int cx = 0; cx < s.replicate_x; ++cx)
      for (auto d : base) {
        d.gid += id_span * (cy * s.replicate_x + cx);
        d.x += Vec2{cx * px, cy * py};
        out.push_back(d);
      }
  return out;
}

}  // namespace

std::vector<SceneDisc> build_scene(const SceneConfig& scene, const Domain& domain, const std::string& config_dir) {
  std::vector<SceneDisc> discs;
  if (scene.type == "lattice_square")
    discs = lattice(scene, false);
  else if (scene.type == "lattice_hex")
    discs = lattice(scene, true);
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
