// scene.type = random: scene.count discs placed by random sequential addition in scene.region, largest first,
// without overlap; radii uniform in radius or in area between scene.radius_min and scene.radius_max (or each
// material's own range), or drawn from the list scene.sizes with scene.fractions. The same discs on any rank
// count (scene.seed); numbered in the order they are placed, or in rows (scene.numbering = rows).
#include "core/ScenePacking.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/ConfigRead.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/MemoryLimit.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace packing {

using config::check;
using config::num;

void check_keys(SceneConfig& s) {
  check(s.count > 0, "scene.count", "must be > 0 for a random scene", std::to_string(s.count));
  if (s.distribution == Distribution::list) {
    check(!s.sizes.empty() && s.sizes.size() == s.fractions.size(), "scene.fractions",
          "one fraction per size in scene.sizes",
          std::to_string(s.fractions.size()) + " fractions for " + std::to_string(s.sizes.size()) + " sizes");
    double sum = 0.0;
    for (double f : s.fractions) sum += f;
    check(std::fabs(sum - 1.0) < 1e-9, "scene.fractions", "fractions must sum to 1", num(sum));
  } else if (s.material_radius_min.empty()) {  // else each material's own range (read_scene_materials)
    check(s.radius_min > 0.0, "scene.radius_min", "must be > 0", num(s.radius_min));
    check(s.radius_max >= s.radius_min, "scene.radius_max", ">= scene.radius_min", num(s.radius_max));
  }
}

std::string radius_keys(const SceneConfig& s) {
  if (s.distribution == Distribution::list) return "scene.sizes";
  if (!s.material_radius_min.empty()) return "scene.material_radius_min, scene.material_radius_max";
  return "scene.radius_min = " + fmt(s.radius_min) + ", scene.radius_max = " + fmt(s.radius_max);
}
std::string placement_keys(const SceneConfig& s) {
  return "scene.count, scene.region (or walls.box_region), " + radius_keys(s);
}

std::pair<double, int> draw_radius(const SceneConfig& s, std::size_t slot, SceneRandom& rng) {
  const double u = rng.uniform();
  const bool own = !s.material_radius_min.empty();
  const double lo = own ? s.material_radius_min[slot] : s.radius_min,
               hi = own ? s.material_radius_max[slot] : s.radius_max;
  if (s.distribution == Distribution::uniform_radius) return {lo + u * (hi - lo), scene::slot_material(s, slot)};
  if (s.distribution == Distribution::uniform_area)
    return {std::sqrt(lo * lo + u * (hi * hi - lo * lo)), scene::slot_material(s, slot)};
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

double largest_radius(const SceneConfig& s) {
  double r = 0.0;
  if (s.distribution == Distribution::list)
    for (double size : s.sizes) r = std::max(r, size);
  else if (!s.material_radius_max.empty())
    for (double m : s.material_radius_max) r = std::max(r, m);
  else
    r = s.radius_max;
  return r;
}

double mean_radius(const SceneConfig& s) {
  const auto mean = [&s](double lo, double hi) {
    if (s.distribution == Distribution::uniform_radius || hi == lo) return 0.5 * (lo + hi);
    return 2.0 / 3.0 * (hi * hi * hi - lo * lo * lo) / (hi * hi - lo * lo);  // uniform in area
  };
  if (s.distribution == Distribution::list) {
    double sum = 0.0;
    for (std::size_t k = 0; k < s.sizes.size(); ++k) sum += s.fractions[k] * s.sizes[k];
    return sum;
  }
  if (s.material_radius_min.empty()) return mean(s.radius_min, s.radius_max);
  const auto n = static_cast<std::size_t>(s.count);
  const std::vector<std::size_t> counts = scene::material_counts(s, n);
  double sum = 0.0;
  for (std::size_t slot = 0; slot < counts.size(); ++slot)
    sum += static_cast<double>(counts[slot]) * mean(s.material_radius_min[slot], s.material_radius_max[slot]);
  return sum / static_cast<double>(n);
}

double smallest_radius(const SceneConfig& s) {
  if (s.distribution == Distribution::list) return *std::min_element(s.sizes.begin(), s.sizes.end());
  if (!s.material_radius_min.empty())
    return *std::min_element(s.material_radius_min.begin(), s.material_radius_min.end());
  return s.radius_min;
}

void check_region(const SceneConfig& s, double r_max) {
  if (s.region[1] - s.region[0] < 2 * r_max || s.region[3] - s.region[2] < 2 * r_max)
    throw InputError(
        "scene.region (empty: walls.box_region, else the domain) is smaller than the largest disc "
        "(diameter " +
        std::to_string(2 * r_max).substr(0, 12) + " m; scene.radius_max, scene.sizes or scene.material_radius_max)");
}

}  // namespace packing

namespace {

using packing::draw_radius;

// Every radius with its material, largest first; equal radii by material (a fixed order for a fixed seed).
std::vector<std::pair<double, int>> draw_radii(const SceneConfig& s, SceneRandom& rng) {
  const auto slots = scene::material_slots(s, static_cast<std::size_t>(s.count));
  std::vector<std::pair<double, int>> radii(static_cast<std::size_t>(s.count));
  for (std::size_t k = 0; k < radii.size(); ++k) radii[k] = draw_radius(s, slots[k], rng);
  std::sort(radii.begin(), radii.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  return radii;
}

// The cells of the overlap checks: side >= the largest diameter, at most about 4 per disc (the placement does
// not depend on the cells: they only find the candidates; a region far larger than the discs gets larger cells).
class PlacementGrid {
 public:
  PlacementGrid(const double (&region)[4], double r_max, std::size_t discs) : x0_(region[0]), y0_(region[2]) {
    const double w = region[1] - region[0], h = region[3] - region[2];
    const double cell = 2.0 * r_max, cap = 4.0 * static_cast<double>(discs) + 64.0;
    double fx = std::clamp(std::floor(w / cell), 1.0, cap), fy = std::clamp(std::floor(h / cell), 1.0, cap);
    while (fx * fy > cap) {
      double& larger = fx >= fy ? fx : fy;
      larger = std::max(1.0, std::floor(0.5 * larger));
    }
    nx_ = static_cast<int>(fx), ny_ = static_cast<int>(fy);
    cx_ = w / nx_, cy_ = h / ny_;
    cells_.resize(static_cast<std::size_t>(nx_) * ny_);
  }
  // Whether a disc of radius R at x overlaps none of `placed`.
  bool free(Vec2 x, double R, const std::vector<SceneDisc>& placed, const Domain& domain) const {
    const auto [ix, iy] = cell_of(x);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        int gx = ix + dx, gy = iy + dy;
        if (domain.periodic_x) gx = (gx + nx_) % nx_;
        if (domain.periodic_y) gy = (gy + ny_) % ny_;
        if (gx < 0 || gx >= nx_ || gy < 0 || gy >= ny_) continue;
        for (std::size_t k : cells_[static_cast<std::size_t>(gy) * nx_ + gx]) {
          const Vec2 d = domain.separation(x, placed[k].x);
          const double reach = R + placed[k].radius;
          if (dot(d, d) < reach * reach) return false;
        }
      }
    return true;
  }
  void add(Vec2 x, std::size_t index) {
    const auto [ix, iy] = cell_of(x);
    cells_[static_cast<std::size_t>(iy) * nx_ + ix].push_back(index);
  }

 private:
  std::pair<int, int> cell_of(Vec2 x) const {
    return {std::min(nx_ - 1, static_cast<int>((x.x - x0_) / cx_)),
            std::min(ny_ - 1, static_cast<int>((x.y - y0_) / cy_))};
  }
  double x0_, y0_, cx_ = 0.0, cy_ = 0.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
};

// Random sequential addition, largest discs first.
std::vector<SceneDisc> random_packing(const SceneInputs& in) {
  const SceneConfig& s = in.scene;
  check_memory(static_cast<double>(s.count), 0.0, 0.0, "scene.count = " + std::to_string(s.count));
  SceneRandom rng(static_cast<std::uint64_t>(s.seed));
  const auto radii = draw_radii(s, rng);
  const double xlo = s.region[0], xhi = s.region[1], ylo = s.region[2], yhi = s.region[3];
  const double r_max = radii.front().first;
  packing::check_region(s, r_max);
  PlacementGrid grid(s.region, r_max, radii.size());
  std::vector<SceneDisc> out;
  out.reserve(radii.size());
  for (const auto& [R, material] : radii) {
    bool placed = false;
    for (std::int64_t attempt = 0; attempt < s.max_attempts && !placed; ++attempt) {
      const Vec2 x{xlo + R + rng.uniform() * (xhi - xlo - 2 * R), ylo + R + rng.uniform() * (yhi - ylo - 2 * R)};
      if (!grid.free(x, R, out, in.domain)) continue;
      grid.add(x, out.size());
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
  if (s.numbering == Numbering::rows) scene::number_in_rows(out, ylo);
  return out;
}

}  // namespace

extern const SceneType kRandomScene{"random",
                                    "scene.count discs placed at random without overlap, largest first",
                                    packing::check_keys,
                                    packing::placement_keys,
                                    packing::radius_keys,
                                    SceneType::Source::keys,
                                    true,
                                    random_packing};

}  // namespace rondel
