// scene.type = lattice_square | lattice_hex: scene.nx x scene.ny discs of scene.radius, the first at
// (scene.x0, scene.y0), centres scene.spacing apart (0: touching); hex rows shifted by half a spacing, sqrt(3)/2
// spacings apart. Numbered row by row, by x within a row.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "core/ConfigRead.hpp"
#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/MemoryLimit.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace {

void check_lattice(SceneConfig& s) {
  config::check(s.nx > 0, "scene.nx", "must be > 0 for a lattice", std::to_string(s.nx));
  config::check(s.ny > 0, "scene.ny", "must be > 0 for a lattice", std::to_string(s.ny));
  config::check(s.radius > 0.0, "scene.radius", "must be > 0 for a lattice", config::num(s.radius));
  if (s.spacing == 0.0) s.spacing = 2.0 * s.radius;
  scene::check_numbering_placement(s);
}

std::string lattice_keys(const SceneConfig&) {
  return "scene.nx, scene.ny, scene.radius, scene.spacing, scene.x0, scene.y0";
}
std::string lattice_radius(const SceneConfig& s) { return "scene.radius = " + fmt(s.radius); }

// The distance between rows, and the position of column i of row j (`row` that distance): one expression for
// every builder, so that each gives the same bits.
double row_step(const SceneConfig& s, bool hex) { return hex ? s.spacing * std::sqrt(3.0) / 2.0 : s.spacing; }
Vec2 position(const SceneConfig& s, bool hex, double row, int i, int j) {
  const double shift = (hex && (j % 2 == 1)) ? 0.5 * s.spacing : 0.0;
  return {s.x0 + i * s.spacing + shift, s.y0 + j * row};
}
// The farthest column's x (a shifted hex row's) and the last row's y.
Vec2 far_corner(const SceneConfig& s, bool hex) {
  return {s.x0 + (s.nx - 1) * s.spacing + (hex && s.ny > 1 ? 0.5 * s.spacing : 0.0),
          s.y0 + (s.ny - 1) * row_step(s, hex)};
}

// The lattice's extent checked against the domain (its corners, the farthest row and column, the half shift of hex
// rows); throws InputError naming the keys.
void check_extent(const SceneInputs& in, bool hex) {
  const SceneConfig& s = in.scene;
  const Domain& domain = in.domain;
  const auto [far_x, far_y] = far_corner(s, hex);
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
}

std::int64_t sites(const SceneConfig& s) { return static_cast<std::int64_t>(s.nx) * s.ny; }

// The lattice's discs one at a time: the site of column i of row j (gid j nx + i) with its material slot from the
// keyed shuffle of the whole lattice's exact counts (scene::material_slot_of: no list of every site).
class Sites {
 public:
  Sites(const SceneConfig& s, bool hex)
      : s_(s),
        hex_(hex),
        row_(row_step(s, hex)),
        n_(static_cast<std::uint64_t>(sites(s))),
        counts_(scene::material_counts(s, n_)) {}
  SceneDisc at(int i, int j) const {
    const std::int64_t k = static_cast<std::int64_t>(j) * s_.nx + i;
    SceneDisc d{k, position(s_, hex_, row_, i, j), s_.radius, s_.velocity, s_.omega};
    d.material = scene::slot_material(s_, scene::material_slot_of(s_, counts_, n_, static_cast<std::uint64_t>(k)));
    return d;
  }

 private:
  const SceneConfig& s_;
  bool hex_;
  double row_;
  std::uint64_t n_;
  std::vector<std::size_t> counts_;
};

// The sites [first, first + count).
std::vector<SceneDisc> lattice_block(const SceneInputs& in, bool hex, std::int64_t first, std::int64_t count) {
  const SceneConfig& s = in.scene;
  check_memory(static_cast<double>(count), 0.0, 0.0, "scene.nx x scene.ny");
  check_extent(in, hex);
  const Sites lattice(s, hex);
  std::vector<SceneDisc> out;
  out.reserve(static_cast<std::size_t>(count));
  for (std::int64_t k = first; k < first + count; ++k)
    out.push_back(lattice.at(static_cast<int>(k % s.nx), static_cast<int>(k / s.nx)));
  return out;
}

// Cell by cell when no site wraps round a periodic side (a site on a periodic side's upper bound would) and the
// grid is untilted; the radius, else 0.
double lattice_by_cells(const SceneInputs& in, bool hex) {
  const SceneConfig& s = in.scene;
  const Domain& d = in.domain;
  const auto [far_x, far_y] = far_corner(s, hex);
  const bool inside_x = !d.periodic_x || (s.x0 >= d.xlo && far_x < d.xhi);
  const bool inside_y = !d.periodic_y || (s.y0 >= d.ylo && far_y < d.yhi);
  return d.tilt == 0.0 && inside_x && inside_y ? s.radius : 0.0;
}

// The lattice seen through an untilted grid: the lattice rows in a range of grid rows, and the sites of a row in a
// range of grid columns, each decided by the grid's own test of the site (every disc's), the candidates from the
// bounds; the grid's rows grow with j and its columns with i, so each answer is a range.
class LatticeWalk {
 public:
  LatticeWalk(const SceneConfig& s, bool hex, const CellGrid& grid)
      : s_(s), hex_(hex), grid_(grid), row_(row_step(s, hex)) {}
  // The rows [first, last] whose sites lie in grid rows cy0 to cy1 (last < first: none).
  std::pair<int, int> rows(int cy0, int cy1) const {
    auto [first, last] =
        span(grid_.cell_corner(0, cy0).y, grid_.cell_corner(0, cy1).y + grid_.cell_sides().y, s_.y0, row_, s_.ny);
    const auto row = [&](int j) { return grid_.row_of(position(s_, hex_, row_, 0, j).y); };
    while (first <= last && row(first) < cy0) ++first;
    while (last >= first && row(last) > cy1) --last;
    return {first, last};
  }
  // The columns [first, last] of row j whose sites lie in grid columns cx0 to cx1 (last < first: none).
  std::pair<int, int> columns(int j, int cx0, int cx1) const {
    const double shift = (hex_ && (j % 2 == 1)) ? 0.5 * s_.spacing : 0.0;
    auto [first, last] = span(grid_.cell_corner(cx0, 0).x, grid_.cell_corner(cx1, 0).x + grid_.cell_sides().x,
                              s_.x0 + shift, s_.spacing, s_.nx);
    const auto column = [&](int i) { return grid_.column_of(position(s_, hex_, row_, i, j)); };
    while (first <= last && column(first) < cx0) ++first;
    while (last >= first && column(last) > cx1) --last;
    return {first, last};
  }

 private:
  // Indices from the one at or below lo to the one at or above hi (in steps from origin), within [0, count).
  static std::pair<int, int> span(double lo, double hi, double origin, double step, int count) {
    const double a = std::clamp(std::floor((lo - origin) / step), 0.0, count - 1.0);
    const double b = std::clamp(std::ceil((hi - origin) / step), 0.0, count - 1.0);
    return {static_cast<int>(a), static_cast<int>(b)};
  }
  const SceneConfig& s_;
  bool hex_;
  const CellGrid& grid_;
  double row_;
};

// The sites in the cells [x0, x1) x [y0, y1): rows of one parity share their columns (a hex row's shift is its
// parity's), so the count is rows x columns for each parity.
std::uint64_t lattice_rect_count(const SceneInputs& in, bool hex, const CellGrid& grid, int x0, int y0, int x1,
                                 int y1) {
  const LatticeWalk walk(in.scene, hex, grid);
  const auto [j0, j1] = walk.rows(y0, y1 - 1);
  std::uint64_t count = 0;
  for (int parity = 0; parity < (hex ? 2 : 1); ++parity) {
    const int j = hex && (j0 % 2 != parity) ? j0 + 1 : j0;  // the first row of this parity
    if (j > j1) continue;
    const auto rows = static_cast<std::uint64_t>(hex ? (j1 - j) / 2 + 1 : j1 - j + 1);
    const auto [i0, i1] = walk.columns(j, x0, x1 - 1);
    if (i1 >= i0) count += rows * static_cast<std::uint64_t>(i1 - i0 + 1);
  }
  return count;
}

// The sites whose cell of `grid` is one of `cells`, in ascending gid: grid row by grid row, the lattice rows in
// it, and along each the sites of each run of adjacent cells of the grid row. Walked twice: first their count (a
// few operations a lattice row and run of cells), then the sites themselves, given to `out`.
void lattice_cells(const SceneInputs& in, bool hex, const CellGrid& grid, std::vector<std::size_t> cells,
                   SceneSink& out) {
  const SceneConfig& s = in.scene;
  // About the share of the sites that these cells' share of the grid holds (a lattice that fills the domain).
  const double share =
      static_cast<double>(sites(s)) * static_cast<double>(cells.size()) / static_cast<double>(grid.size());
  check_memory(share, 0.0, 0.0, "scene.nx x scene.ny");
  check_extent(in, hex);
  const LatticeWalk walk(s, hex, grid);
  if (!std::is_sorted(cells.begin(), cells.end())) std::sort(cells.begin(), cells.end());  // row-major
  const auto nx = static_cast<std::size_t>(grid.nx());
  // Calls site(first, last, j) for each run of sites [first, last] of lattice row j, in ascending gid.
  const auto walk_sites = [&](auto&& site) {
    for (std::size_t r0 = 0; r0 < cells.size();) {
      std::size_t r1 = r0;
      while (r1 < cells.size() && cells[r1] / nx == cells[r0] / nx) ++r1;  // this grid row's cells: [r0, r1)
      const int cy = static_cast<int>(cells[r0] / nx);
      const auto [j0, j1] = walk.rows(cy, cy);
      for (int j = j0; j <= j1; ++j) {
        for (std::size_t a = r0; a < r1;) {
          std::size_t b = a + 1;  // a run of adjacent cells [a, b)
          while (b < r1 && cells[b] == cells[b - 1] + 1) ++b;
          const auto [first, last] =
              walk.columns(j, static_cast<int>(cells[a] % nx), static_cast<int>(cells[b - 1] % nx));
          site(first, last, j);
          a = b;
        }
      }
      r0 = r1;
    }
  };
  std::size_t count = 0;
  walk_sites([&](int first, int last, int) { count += static_cast<std::size_t>(std::max(last - first + 1, 0)); });
  out.reserve(count);
  const Sites lattice(s, hex);
  walk_sites([&](int first, int last, int j) {
    for (int i = first; i <= last; ++i) out.add(lattice.at(i, j));
  });
}

std::vector<SceneDisc> lattice(const SceneInputs& in, bool hex) { return lattice_block(in, hex, 0, sites(in.scene)); }

std::vector<SceneDisc> square(const SceneInputs& in) { return lattice(in, false); }
std::vector<SceneDisc> hexagonal(const SceneInputs& in) { return lattice(in, true); }
std::vector<SceneDisc> square_block(const SceneInputs& in, std::int64_t first, std::int64_t count) {
  return lattice_block(in, false, first, count);
}
double square_by_cells(const SceneInputs& in) { return lattice_by_cells(in, false); }
std::uint64_t square_count(const SceneInputs& in, const CellGrid& grid, int x0, int y0, int x1, int y1) {
  return lattice_rect_count(in, false, grid, x0, y0, x1, y1);
}
std::uint64_t hexagonal_count(const SceneInputs& in, const CellGrid& grid, int x0, int y0, int x1, int y1) {
  return lattice_rect_count(in, true, grid, x0, y0, x1, y1);
}
double hexagonal_by_cells(const SceneInputs& in) { return lattice_by_cells(in, true); }
void square_cells(const SceneInputs& in, const CellGrid& grid, const std::vector<std::size_t>& c, SceneSink& out) {
  lattice_cells(in, false, grid, c, out);
}
void hexagonal_cells(const SceneInputs& in, const CellGrid& grid, const std::vector<std::size_t>& c, SceneSink& out) {
  lattice_cells(in, true, grid, c, out);
}
std::vector<SceneDisc> hexagonal_block(const SceneInputs& in, std::int64_t first, std::int64_t count) {
  return lattice_block(in, true, first, count);
}

}  // namespace

extern const SceneType kLatticeSquareScene{"lattice_square",
                                           "scene.nx x scene.ny discs on a square lattice",
                                           check_lattice,
                                           lattice_keys,
                                           lattice_radius,
                                           SceneType::Source::keys,
                                           false,
                                           square,
                                           sites,
                                           square_block,
                                           square_by_cells,
                                           square_count,
                                           square_cells};
extern const SceneType kLatticeHexScene{"lattice_hex",
                                        "scene.nx x scene.ny discs on a hexagonal lattice",
                                        check_lattice,
                                        lattice_keys,
                                        lattice_radius,
                                        SceneType::Source::keys,
                                        false,
                                        hexagonal,
                                        sites,
                                        hexagonal_block,
                                        hexagonal_by_cells,
                                        hexagonal_count,
                                        hexagonal_cells};

}  // namespace rondel
