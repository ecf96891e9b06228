// scene.type = random_tiles: scene.count discs placed at random without overlap, tile by tile, so that each rank
// places only the discs near its own cells and the scene is the same disc for disc on any rank count
// (docs/scaling.md, "Set-up"; the keys are the random packing's, core/ScenePacking.hpp).
//
// scene.region is cut into tiles at least a largest diameter across, about kDiscsPerTile discs each, from the keys
// alone. Tile t holds an equal share of scene.count (the remainder spread evenly) and the ids [first(t), first(t) +
// n(t)), numbered tile by tile in rows; its radii and positions come from a generator keyed by (scene.seed, t). The
// tiles are placed in four phases by their colour (column and row parity): a tile places its discs largest first,
// by random sequential addition, against its own and those of its neighbours of earlier phases, a disc reaching at
// most kReach of its radius into a tile of a later phase. Two tiles of one colour are a tile apart, so no disc of
// one can touch a disc of the other: a tile's discs depend only on the tiles of earlier phases round it, at most
// three tiles away, and a rank places the tiles of its cells and that halo.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/Errors.hpp"
#include "core/Format.hpp"
#include "core/MemoryLimit.hpp"
#include "core/ScenePacking.hpp"
#include "core/SceneTypes.hpp"

namespace rondel {

namespace {

// About this many discs a tile (fewer: a thinner halo, but a packing less dense than random's at most).
constexpr double kDiscsPerTile = 64.0;
// A disc reaches at most this much of its radius across a tile's side into a tile of a later phase. With 0, the
// last phase's tiles are crowded by their neighbours' discs and refuse first (a monodisperse packing fraction of
// 0.41 at most with 32 discs a tile, against random's 0.47); with 1, the first phase's; 0.5 places 0.45
// (docs/scaling.md).
constexpr double kReach = 0.5;

// The tiles of scene.region and what each holds.
class Tiles {
 public:
  explicit Tiles(const SceneConfig& s)
      : s_(s), r_max_(packing::largest_radius(s)), rho_(0.5 * (packing::smallest_radius(s) + r_max_)) {
    packing::check_region(s, r_max_);
    const double w = s.region[1] - s.region[0] - 2.0 * rho_, h = s.region[3] - s.region[2] - 2.0 * rho_;
    const double n = static_cast<double>(s.count);
    // A little over a diameter, so that rounding never brings two tiles of one colour within reach.
    const double side = std::max(2.0 * r_max_ * (1.0 + 1e-9), std::sqrt(kDiscsPerTile * w * h / n));
    nx_ = static_cast<std::int64_t>(std::clamp(std::floor(w / side), 1.0, n));
    ny_ = static_cast<std::int64_t>(std::clamp(std::floor(h / side), 1.0, std::max(1.0, std::floor(n / nx_))));
    total_ = nx_ * ny_;
    q_ = s.count / total_, rem_ = s.count % total_;
  }
  std::int64_t nx() const { return nx_; }
  std::int64_t ny() const { return ny_; }
  std::int64_t size() const { return total_; }
  double r_max() const { return r_max_; }
  // The ids of tile t start here; n(t) = first(t + 1) - first(t), q or q + 1 (the remainder spread evenly).
  std::int64_t first(std::int64_t t) const {
    __extension__ typedef __int128 Wide;
    return q_ * t + static_cast<std::int64_t>(static_cast<Wide>(rem_) * t / total_);
  }
  std::int64_t discs(std::int64_t t) const { return first(t + 1) - first(t); }
  static int colour(std::int64_t ix, std::int64_t iy) { return static_cast<int>((ix & 1) + 2 * (iy & 1)); }
  int colour(std::int64_t t) const { return colour(t % nx_, t / nx_); }
  // Tile bounds: column ix holds x in [x_at(ix), x_at(ix + 1)). The tiles cut the region less a mean radius rho
  // at each side into equal parts and the edge tiles take that strip too: a disc's centre keeps its radius from the
  // region's sides, so every tile has about the same room for its equal share of the discs.
  double x_at(std::int64_t ix) const { return at(ix, nx_, s_.region[0], s_.region[1]); }
  double y_at(std::int64_t iy) const { return at(iy, ny_, s_.region[2], s_.region[3]); }
  // The column and row of the tiles that a coordinate falls in, clamped into the region.
  std::int64_t column(double x) const { return along(x, s_.region[0], s_.region[1], nx_); }
  std::int64_t row(double y) const { return along(y, s_.region[2], s_.region[3], ny_); }
  // f(u) for each tile u of the 3 x 3 around t (t itself included).
  template <class F>
  void around(std::int64_t t, F f) const {
    const std::int64_t ix = t % nx_, iy = t / nx_;
    for (std::int64_t y = std::max<std::int64_t>(iy - 1, 0); y <= std::min(iy + 1, ny_ - 1); ++y)
      for (std::int64_t x = std::max<std::int64_t>(ix - 1, 0); x <= std::min(ix + 1, nx_ - 1); ++x) f(y * nx_ + x);
  }

 private:
  double at(std::int64_t i, std::int64_t n, double lo, double hi) const {
    if (i <= 0) return lo;
    if (i >= n) return hi;
    return lo + rho_ + (hi - lo - 2.0 * rho_) * static_cast<double>(i) / static_cast<double>(n);
  }
  std::int64_t along(double v, double lo, double hi, std::int64_t n) const {
    if (n == 1) return 0;
    const double f = std::floor((v - lo - rho_) / (hi - lo - 2.0 * rho_) * static_cast<double>(n));
    return static_cast<std::int64_t>(std::clamp(f, 0.0, static_cast<double>(n - 1)));
  }
  const SceneConfig& s_;
  double r_max_, rho_;
  std::int64_t nx_ = 1, ny_ = 1, total_ = 1, q_ = 0, rem_ = 0;
};

// The discs near a tile in bins a largest diameter across, over the tile widened by that diameter (a disc centred
// farther out cannot touch one centred in the tile): whether a new disc is free looks in the 3 x 3 bins round it.
class Bins {
 public:
  void reset(double x0, double y0, double x1, double y1, double side) {
    x0_ = x0, y0_ = y0, side_ = side;
    nx_ = std::max(1, static_cast<int>(std::ceil((x1 - x0) / side))),
    ny_ = std::max(1, static_cast<int>(std::ceil((y1 - y0) / side)));
    if (bins_.size() < static_cast<std::size_t>(nx_) * ny_) bins_.resize(static_cast<std::size_t>(nx_) * ny_);
    for (auto& b : bins_) b.clear();
  }
  void add(Vec2 x, double r) {
    const int cx = bin(x.x, x0_, nx_), cy = bin(x.y, y0_, ny_);
    if (cx >= 0 && cy >= 0) bins_[static_cast<std::size_t>(cy) * nx_ + cx].push_back({x, r});
  }
  bool free(Vec2 x, double R) const {
    const int cx = bin(x.x, x0_, nx_), cy = bin(x.y, y0_, ny_);
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, ny_ - 1); ++y)
      for (int c = std::max(cx - 1, 0); c <= std::min(cx + 1, nx_ - 1); ++c)
        for (const Entry& d : bins_[static_cast<std::size_t>(y) * nx_ + c]) {
          const Vec2 e = x - d.x;
          const double reach = R + d.r;
          if (dot(e, e) < reach * reach) return false;
        }
    return true;
  }

 private:
  struct Entry {
    Vec2 x;
    double r;
  };
  int bin(double v, double lo, int n) const {  // -1 outside
    const double f = std::floor((v - lo) / side_);
    return f >= 0.0 && f < n ? static_cast<int>(f) : -1;
  }
  double x0_ = 0.0, y0_ = 0.0, side_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<Entry>> bins_;
};

// A disc placed: what it does not share with the others of its scene (its id is its tile's first plus its rank in
// the tile), 32 B where a SceneDisc takes 64.
struct Placed {
  Vec2 x;
  double radius;
  int material;
};

// Tiles and their discs, ascending by tile.
struct TileSet {
  std::vector<std::int64_t> tiles;
  std::vector<std::vector<Placed>> discs;
  const std::vector<Placed>* find(std::int64_t t) const {
    const auto it = std::lower_bound(tiles.begin(), tiles.end(), t);
    return it != tiles.end() && *it == t ? &discs[static_cast<std::size_t>(it - tiles.begin())] : nullptr;
  }
  // Disc j of the k-th tile, whole; `first` is the tile's first id (Tiles::first).
  SceneDisc disc(const SceneConfig& s, std::int64_t first, std::size_t k, std::size_t j) const {
    const Placed& p = discs[k][j];
    return {first + static_cast<std::int64_t>(j), p.x, p.radius, s.velocity, s.omega, p.material};
  }
};

// The tiles that `targets` (sorted, distinct) need placed: themselves and, for each, its neighbours of earlier
// phases, theirs in turn.
std::vector<std::int64_t> with_earlier_phases(const Tiles& tiles, std::vector<std::int64_t> set) {
  for (int phase = 3; phase >= 1; --phase) {
    const std::size_t n = set.size();
    for (std::size_t k = 0; k < n; ++k)
      if (tiles.colour(set[k]) == phase)
        tiles.around(set[k], [&](std::int64_t u) {
          if (tiles.colour(u) < phase) set.push_back(u);
        });
    std::sort(set.begin(), set.end());
    set.erase(std::unique(set.begin(), set.end()), set.end());
  }
  return set;
}

[[noreturn]] void refuse(const SceneConfig& s, const Tiles& tiles) {
  std::ostringstream m;
  m << "scene.count = " << s.count << ": the discs do not fit in scene.region without overlap: placed tile by tile ("
    << tiles.nx() << " x " << tiles.ny() << " tiles of about " << s.count / tiles.size()
    << " discs), a tile could not place one of its discs after scene.max_attempts = " << s.max_attempts
    << " tries; lower scene.count or the radii, or enlarge scene.region (scene.type = random, largest first over the "
       "whole region, packs a little denser)";
  throw InputError(m.str());
}

// Places the discs of the tiles of `set`, phase by phase; each tile sees its own discs and those of its neighbours
// of earlier phases (all in `set`, with_earlier_phases).
TileSet place(const SceneConfig& s, const Tiles& tiles, const std::vector<std::int64_t>& set) {
  TileSet out{set, std::vector<std::vector<Placed>>(set.size())};
  const auto n = static_cast<std::uint64_t>(s.count);
  const std::vector<std::size_t> counts = scene::material_counts(s, static_cast<std::size_t>(n));
  Bins near;  // the discs of the tile and of its neighbours of earlier phases
  std::vector<std::pair<double, int>> radii;
  const double reach = 2.0 * tiles.r_max();
  for (int phase = 0; phase < 4; ++phase)
    for (std::size_t k = 0; k < set.size(); ++k) {
      const std::int64_t t = set[k];
      if (tiles.colour(t) != phase) continue;
      const std::int64_t ix = t % tiles.nx(), iy = t / tiles.nx();
      near.reset(tiles.x_at(ix) - reach, tiles.y_at(iy) - reach, tiles.x_at(ix + 1) + reach, tiles.y_at(iy + 1) + reach,
                 reach);
      tiles.around(t, [&](std::int64_t u) {
        if (tiles.colour(u) < phase)
          for (const Placed& d : *out.find(u)) near.add(d.x, d.radius);
      });
      // The tile's generator: its stream apart from every other tile's.
      SceneRandom rng(SceneRandom(static_cast<std::uint64_t>(s.seed) ^
                                  (static_cast<std::uint64_t>(t) * 0xD1B54A32D192ED03ull + 0x8BB84B93962EACC9ull))
                          .next());
      const std::int64_t first = tiles.first(t), count = tiles.discs(t);
      radii.resize(static_cast<std::size_t>(count));
      for (std::int64_t j = 0; j < count; ++j)
        radii[static_cast<std::size_t>(j)] =
            packing::draw_radius(s, scene::material_slot_of(s, counts, n, static_cast<std::uint64_t>(first + j)), rng);
      std::sort(radii.begin(), radii.end(), [](const auto& a, const auto& b) {
        return a.first > b.first || (a.first == b.first && a.second < b.second);
      });
      std::vector<Placed>& mine = out.discs[k];
      mine.reserve(radii.size());
      for (const auto& [R, material] : radii) {
        // The sides across which the tiles of later phases lie: a tile of an even column has them left and right, of
        // an even row above and below.
        const double ex = (ix & 1) == 0 ? kReach * R : 0.0, ey = (iy & 1) == 0 ? kReach * R : 0.0;
        const double x0 = std::max(tiles.x_at(ix) + ex, s.region[0] + R),
                     x1 = std::min(tiles.x_at(ix + 1) - ex, s.region[1] - R);
        const double y0 = std::max(tiles.y_at(iy) + ey, s.region[2] + R),
                     y1 = std::min(tiles.y_at(iy + 1) - ey, s.region[3] - R);
        bool placed = false;
        for (std::int64_t attempt = 0; attempt < s.max_attempts && !placed; ++attempt) {
          const Vec2 x{x0 + rng.uniform() * (x1 - x0), y0 + rng.uniform() * (y1 - y0)};
          if (!near.free(x, R)) continue;
          near.add(x, R);
          mine.push_back({x, R, material});
          placed = true;
        }
        if (!placed) refuse(s, tiles);
      }
    }
  return out;
}

// The region must lie inside the domain (a disc placed outside it would be refused by one rank only).
void check_inside(const SceneInputs& in) {
  const SceneConfig& s = in.scene;
  const Domain& d = in.domain;
  if (s.region[0] < d.xlo || s.region[1] > d.xhi || s.region[2] < d.ylo || s.region[3] > d.yhi)
    throw InputError("scene.region (empty: walls.box_region, else the domain) = " + fmt(s.region[0]) + " " +
                     fmt(s.region[1]) + " " + fmt(s.region[2]) + " " + fmt(s.region[3]) +
                     " must lie inside the domain [" + fmt(d.xlo) + ", " + fmt(d.xhi) + "] x [" + fmt(d.ylo) + ", " +
                     fmt(d.yhi) + "] for scene.type = random_tiles");
}

std::vector<SceneDisc> tiles_build(const SceneInputs& in) {
  const SceneConfig& s = in.scene;
  check_inside(in);
  check_memory(static_cast<double>(s.count), 0.0, 0.0, "scene.count = " + std::to_string(s.count));
  const Tiles tiles(s);
  std::vector<std::int64_t> all(static_cast<std::size_t>(tiles.size()));
  for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<std::int64_t>(t);
  TileSet placed = place(s, tiles, all);
  std::vector<SceneDisc> out;
  out.reserve(static_cast<std::size_t>(s.count));
  for (std::size_t k = 0; k < placed.tiles.size(); ++k) {
    const std::int64_t first = tiles.first(placed.tiles[k]);
    for (std::size_t j = 0; j < placed.discs[k].size(); ++j) out.push_back(placed.disc(s, first, k, j));
    std::vector<Placed>().swap(placed.discs[k]);
  }
  return out;
}

// Cell by cell in an untilted domain; the largest radius the keys allow (the grid's range).
double tiles_by_cells(const SceneInputs& in) { return in.domain.tilt == 0.0 ? packing::largest_radius(in.scene) : 0.0; }

// The expected count: scene.count by the share of scene.region that the rectangle of cells covers (the first
// partition's weights; a tile's count differs from its share of scene.count by less than one disc).
std::uint64_t tiles_rect_count(const SceneInputs& in, const CellGrid& grid, int x0, int y0, int x1, int y1) {
  const SceneConfig& s = in.scene;
  const Vec2 lo = grid.cell_corner(x0, y0), hi = grid.cell_corner(x1 - 1, y1 - 1) + grid.cell_sides();
  // The edge cells of the grid hold what lies beyond it too.
  const double ax = x0 == 0 ? -INFINITY : lo.x, bx = x1 == grid.nx() ? INFINITY : hi.x;
  const double ay = y0 == 0 ? -INFINITY : lo.y, by = y1 == grid.ny() ? INFINITY : hi.y;
  const double w = std::max(0.0, std::min(bx, s.region[1]) - std::max(ax, s.region[0]));
  const double h = std::max(0.0, std::min(by, s.region[3]) - std::max(ay, s.region[2]));
  const double share = w * h / ((s.region[1] - s.region[0]) * (s.region[3] - s.region[2]));
  return static_cast<std::uint64_t>(std::llround(share * static_cast<double>(s.count)));
}

// The tiles that the cells (sorted, row-major) meet: for each run of adjacent cells of a grid row, the tiles
// under its rectangle, as rows of tile columns merged before they are listed.
std::vector<std::int64_t> tiles_of_cells(const Tiles& tiles, const CellGrid& grid,
                                         const std::vector<std::size_t>& cells) {
  struct Span {
    std::int64_t row, lo, hi;
  };
  std::vector<Span> spans;
  const auto nx = static_cast<std::size_t>(grid.nx());
  for (std::size_t a = 0; a < cells.size();) {
    std::size_t b = a + 1;
    while (b < cells.size() && cells[b] == cells[b - 1] + 1 && cells[b] / nx == cells[a] / nx) ++b;
    const int cy = static_cast<int>(cells[a] / nx);
    const Vec2 lo = grid.cell_corner(static_cast<int>(cells[a] % nx), cy);
    const Vec2 hi = grid.cell_corner(static_cast<int>(cells[b - 1] % nx), cy) + grid.cell_sides();
    for (std::int64_t r = tiles.row(lo.y); r <= tiles.row(hi.y); ++r)
      spans.push_back({r, tiles.column(lo.x), tiles.column(hi.x)});
    a = b;
  }
  std::sort(spans.begin(), spans.end(),
            [](const Span& p, const Span& q) { return p.row != q.row ? p.row < q.row : p.lo < q.lo; });
  std::vector<std::int64_t> out;
  for (std::size_t k = 0; k < spans.size();) {
    std::int64_t lo = spans[k].lo, hi = spans[k].hi;
    const std::int64_t row = spans[k].row;
    for (++k; k < spans.size() && spans[k].row == row && spans[k].lo <= hi + 1; ++k) hi = std::max(hi, spans[k].hi);
    for (std::int64_t c = lo; c <= hi; ++c) out.push_back(row * tiles.nx() + c);
  }
  return out;
}

// The discs whose cell is one of `cells`, in ascending gid (tile by tile), given to `out` after their count.
void tiles_cells(const SceneInputs& in, const CellGrid& grid, const std::vector<std::size_t>& given, SceneSink& out) {
  const SceneConfig& s = in.scene;
  check_inside(in);
  check_memory(static_cast<double>(s.count) * static_cast<double>(given.size()) / static_cast<double>(grid.size()), 0.0,
               0.0, "scene.count = " + std::to_string(s.count));
  std::vector<std::size_t> cells = given;
  if (!std::is_sorted(cells.begin(), cells.end())) std::sort(cells.begin(), cells.end());
  const Tiles tiles(s);
  TileSet placed = place(s, tiles, with_earlier_phases(tiles, tiles_of_cells(tiles, grid, cells)));
  // Whether all, none or some of a tile's discs lie in these cells, from the cells its rectangle meets.
  enum class Share { all, none, some };
  const auto own = [&](Vec2 x) { return std::binary_search(cells.begin(), cells.end(), grid.cell_of(x)); };
  std::vector<Share> share(placed.tiles.size());
  for (std::size_t k = 0; k < placed.tiles.size(); ++k) {
    const std::int64_t ix = placed.tiles[k] % tiles.nx(), iy = placed.tiles[k] / tiles.nx();
    const Vec2 lo{tiles.x_at(ix), tiles.y_at(iy)}, hi{tiles.x_at(ix + 1), tiles.y_at(iy + 1)};
    std::size_t in = 0, of = 0;
    for (int cy = grid.row_of(lo.y); cy <= grid.row_of(hi.y); ++cy)
      for (int cx = grid.column_of(lo); cx <= grid.column_of(hi); ++cx, ++of)
        in += std::binary_search(cells.begin(), cells.end(), grid.index(cx, cy));
    share[k] = in == of ? Share::all : in == 0 ? Share::none : Share::some;
  }
  const auto mine = [&](std::size_t k, std::size_t j) {
    return share[k] == Share::all || (share[k] == Share::some && own(placed.discs[k][j].x));
  };
  std::size_t count = 0;
  for (std::size_t k = 0; k < placed.tiles.size(); ++k)
    for (std::size_t j = 0; j < placed.discs[k].size(); ++j) count += mine(k, j);
  out.reserve(count);
  for (std::size_t k = 0; k < placed.tiles.size(); ++k) {
    const std::int64_t first = tiles.first(placed.tiles[k]);
    for (std::size_t j = 0; j < placed.discs[k].size(); ++j)
      if (mine(k, j)) out.add(placed.disc(s, first, k, j));
    std::vector<Placed>().swap(placed.discs[k]);
  }
}

void check_tiles(SceneConfig& s) {
  packing::check_keys(s);
  scene::check_numbering_placement(s);
}

}  // namespace

extern const SceneType kRandomTilesScene{"random_tiles",
                                         "scene.count discs placed at random without overlap, tile by tile (each "
                                         "rank its own; the same scene on any rank count)",
                                         check_tiles,
                                         packing::placement_keys,
                                         packing::radius_keys,
                                         SceneType::Source::keys,
                                         true,
                                         tiles_build,
                                         nullptr,
                                         nullptr,
                                         tiles_by_cells,
                                         tiles_rect_count,
                                         tiles_cells,
                                         packing::mean_radius};

}  // namespace rondel
