#pragma once
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
  // The column (in reduced coordinates) and the row of the cell of x, clamped like cell_of.
  int column_of(Vec2 x) const;
  int row_of(double y) const;
  std::size_t index(int cx, int cy) const { return static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + cx; }
  bool periodic_x() const { return domain_.periodic_x; }
  bool periodic_y() const { return domain_.periodic_y; }
  // The distinct cells of the 3 x 3 stencil around `cell` (periodic wrap; itself included), ascending.
  std::vector<std::size_t> stencil(std::size_t cell) const;

 private:
  Domain domain_;
  int nx_ = 1, ny_ = 1;
  double side_x_ = 1.0, side_y_ = 1.0;
};

}  // namespace rondel
