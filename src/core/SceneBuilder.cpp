#include "core/SceneBuilder.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/ConfigRead.hpp"
#include "core/Errors.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

std::uint64_t SceneRandom::next() {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

namespace scene {

namespace {

// The mean R^2 of the discs of material slot k (scene.material_by = area turns area fractions into numbers).
double mean_square_radius(const SceneConfig& s, std::size_t k) {
  if (s.material_radius_min.empty()) return 1.0;  // one radius law for every material: the areas cancel
  const double a = s.material_radius_min[k], b = s.material_radius_max[k];
  return s.distribution == Distribution::uniform_area ? 0.5 * (a * a + b * b) : (a * a + a * b + b * b) / 3.0;
}

}  // namespace

std::vector<std::size_t> material_counts(const SceneConfig& s, std::size_t n) {
  const std::size_t m = s.materials.size();
  if (m == 0) return {n};
  std::vector<double> w(m);
  double total = 0.0;
  for (std::size_t k = 0; k < m; ++k)
    total += w[k] = s.material_by == MaterialBy::area ? s.material_fractions[k] / mean_square_radius(s, k)
                                                      : s.material_fractions[k];
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
  return count;
}

std::vector<std::size_t> material_slots(const SceneConfig& s, std::size_t n) {
  if (s.materials.empty()) return std::vector<std::size_t>(n, 0);
  const std::vector<std::size_t> count = material_counts(s, n);
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < count.size(); ++k) out.insert(out.end(), count[k], k);
  // Its own generator: the positions and radii draw the same numbers with or without materials.
  SceneRandom rng(static_cast<std::uint64_t>(s.seed) ^ 0x6d6174657269616cULL);  // "material"
  for (std::size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[rng.next() % i]);
  return out;
}

int slot_material(const SceneConfig& s, std::size_t slot) { return s.materials.empty() ? 0 : s.materials[slot]; }

std::uint64_t keyed_permutation(std::uint64_t k, std::uint64_t n, std::uint64_t key) {
  // Four Feistel rounds over 2h bits, 2^(2h) >= n; a value at or above n is permuted again (cycle walking: fewer
  // than four rounds on average, since 2^(2h) < 4 n).
  int h = 1;
  while ((std::uint64_t{1} << (2 * h)) < n) ++h;
  const std::uint64_t mask = (std::uint64_t{1} << h) - 1;
  const auto round = [&](std::uint64_t x) {
    std::uint64_t left = x >> h, right = x & mask;
    for (std::uint64_t r = 0; r < 4; ++r) {
      SceneRandom f(key ^ (right * 0x9e3779b97f4a7c15ULL) ^ (r << 56));
      const std::uint64_t next = left ^ (f.next() & mask);
      left = right, right = next;
    }
    return (left << h) | right;
  };
  std::uint64_t y = round(k);
  while (y >= n) y = round(y);
  return y;
}

std::size_t material_slot_of(const SceneConfig& s, const std::vector<std::size_t>& counts, std::uint64_t n,
                             std::uint64_t k) {
  if (s.materials.empty()) return 0;
  std::uint64_t place = keyed_permutation(k, n, static_cast<std::uint64_t>(s.seed) ^ 0x6d6174657269616cULL);
  std::size_t slot = 0;
  while (place >= counts[slot]) place -= counts[slot++];
  return slot;
}

// The kernel reads the discs in id order (docs/design.md section 5): ids that follow space keep a disc's partners
// a row of ids away, so its reads stream (docs/benchmarks.md, "The order of the ids"). Ties keep their order.
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

void check_numbering_placement(const SceneConfig& s) {
  config::check(s.numbering == Numbering::placement, "scene.numbering",
                "only with scene.type = random (lattices and replicated copies are numbered in rows, random_tiles "
                "tile by tile in rows, a csv file keeps its ids)",
                std::string("rows with scene.type = ") + s.type->name);
}

std::string resolve(const std::string& file, const std::string& config_dir) {
  namespace fs = std::filesystem;
  if (fs::path(file).is_absolute() || fs::exists(file) || config_dir.empty()) return file;
  const fs::path alt = fs::path(config_dir) / file;
  return fs::exists(alt) ? alt.string() : file;
}

}  // namespace scene

namespace scene {
bool in_blocks(const SceneConfig& s) {
  return s.type->block != nullptr || s.type->source == SceneType::Source::state_file ||
         s.type->source == SceneType::Source::csv_file;
}
double by_cells(const SceneInputs& in) {
  const SceneType& t = *in.scene.type;
  return t.by_cells && t.rect_count && t.cells ? t.by_cells(in) : 0.0;
}
}  // namespace scene

std::vector<SceneDisc> build_scene_block(const SceneInputs& in, int rank, int ranks) {
  const std::int64_t n = in.scene.type->total(in.scene);
  // floor(N r / P) = q r + floor(rem r / P) for N = q P + rem: no product above 2^62.
  const std::int64_t q = n / ranks, rem = n % ranks;
  const auto first_of = [&](int r) { return q * r + rem * r / ranks; };
  return in.scene.type->block(in, first_of(rank), first_of(rank + 1) - first_of(rank));
}

std::vector<SceneDisc> build_scene(const SceneInputs& in) {
  std::vector<SceneDisc> discs = in.scene.type->build(in);
  std::sort(discs.begin(), discs.end(), [](const SceneDisc& a, const SceneDisc& b) { return a.gid < b.gid; });
  for (std::size_t k = 1; k < discs.size(); ++k)
    if (discs[k].gid == discs[k - 1].gid)
      throw InputError("scene: disc id " + std::to_string(discs[k].gid) + " appears twice");
  return discs;
}

}  // namespace rondel
