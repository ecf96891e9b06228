#pragma once
#include <cstddef>
#include <vector>

#include "core/Domain.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// A regular grid of cells over the domain with side >= a given range (the interaction range), the same on
// every rank. Positions outside a non-periodic box are clamped into the edge cells, which keeps the
// 3 x 3 stencil complete (the mapping is monotone). Used by the neighbour search and by the domain
// decomposition (cells are what the partitioners assign to ranks).
class CellGrid {
 public:
  CellGrid() = default;
  CellGrid(const Domain& domain, double range);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  std::size_t size() const { return static_cast<std::size_t>(nx_) * ny_; }
  std::size_t cell_of(Vec2 x) const;
  // The column and row of the cell of x (clamped like cell_of) and back.
  int column_of(double x) const;
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
