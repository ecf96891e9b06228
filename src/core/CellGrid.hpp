#pragma once
#include <cmath>
#include <cstddef>
#include <vector>

#include "core/Domain.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// A regular grid of cells over the domain, at least a given range (the interaction range) across in both
// directions, the same on every rank. In a tilted cell the grid is one of reduced coordinates: the column of x
// is that of x_x - shear_shift(x_y), so its cells are parallelograms with the cell's slanted sides, and a
// disc's neighbours across the sheared boundary are in the 3 x 3 stencil as anywhere else (docs/physics.md
// section 10). Positions outside a non-periodic box are clamped into the edge cells, which keeps the 3 x 3
// stencil complete (the mapping is monotone). Used by the neighbour search and by the domain decomposition
// (cells are what the partitioners assign to ranks).
class CellGrid {
 public:
  CellGrid() = default;
  // The cells of `domain` now (its tilt as it is).
  CellGrid(const Domain& domain, double range) : CellGrid(domain, range, domain) {}
  // The counts of the grid that stays wide enough on `sizing` (the smallest, most tilted cell of a run: a
  // decomposition's grid serves the whole run), its geometry `domain`'s.
  CellGrid(const Domain& domain, double range, const Domain& sizing);
  // The geometry of the cell now, the counts kept (a deforming cell's grid deforms with it).
  void follow(const Domain& domain);
  // The width across the columns' slanted sides and the rows' height of `domain` with this grid's counts.
  double column_width(const Domain& domain) const;
  double row_height(const Domain& domain) const { return domain.length_y() / ny_; }

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  std::size_t size() const { return static_cast<std::size_t>(nx_) * ny_; }
  std::size_t cell_of(Vec2 x) const { return index(column_of(x), row_of(x.y)); }
  // The column (in reduced coordinates) and the row of the cell of x, clamped like cell_of. Inline: they run for
  // every disc of every neighbour list, migration and ghost exchange.
  int column_of(Vec2 x) const { return clamp_index(x.x - domain_.shear_shift(x.y), domain_.xlo, side_x_, nx_); }
  int row_of(double y) const { return clamp_index(y, domain_.ylo, side_y_, ny_); }
  std::size_t index(int cx, int cy) const { return static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + cx; }
  bool periodic_x() const { return domain_.periodic_x; }
  bool periodic_y() const { return domain_.periodic_y; }
  // The distinct cells of the 3 x 3 stencil around `cell` (periodic wrap; itself included), ascending.
  std::vector<std::size_t> stencil(std::size_t cell) const;
  // f(cx, cy) for each cell of that stencil without building the list: a cell may come more than once (a
  // periodic grid of one or two cells across), in no set order.
  template <class F>
  void for_each_in_stencil(std::size_t cell, F f) const {
    const int cx = static_cast<int>(cell % static_cast<std::size_t>(nx_)), cy = static_cast<int>(cell / nx_);
    // One step past an edge wraps by one length (no division: this runs for every cell and disc).
    const auto wrap = [](int v, int n, bool periodic) { return !periodic ? v : v < 0 ? v + n : v >= n ? v - n : v; };
    for (int dy = -1; dy <= 1; ++dy) {
      const int y = wrap(cy + dy, ny_, domain_.periodic_y);
      if (y < 0 || y >= ny_) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = wrap(cx + dx, nx_, domain_.periodic_x);
        if (x >= 0 && x < nx_) f(x, y);
      }
    }
  }
  // The lower corner of cell (cx, cy) and its sides, in the reduced coordinates of column_of (an untilted cell's
  // own): the cell holds [lo, lo + side) in each direction (the edge cells of a box also what lies beyond it).
  Vec2 cell_corner(int cx, int cy) const { return {domain_.xlo + cx * side_x_, domain_.ylo + cy * side_y_}; }
  Vec2 cell_sides() const { return {side_x_, side_y_}; }

 private:
  static int clamp_index(double coord, double lo, double side, int n) {
    const double c = std::floor((coord - lo) / side);
    if (!(c >= 0.0)) return 0;  // also catches NaN
    if (c >= n - 1) return n - 1;
    return static_cast<int>(c);
  }

  Domain domain_;
  int nx_ = 1, ny_ = 1;
  double side_x_ = 1.0, side_y_ = 1.0;
};

}  // namespace rondel
