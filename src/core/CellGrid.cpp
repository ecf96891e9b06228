#include "core/CellGrid.hpp"

#include <algorithm>
#include <cmath>

namespace rondel {

namespace {
int cell_count(double length, double range) {
  const double n = std::floor(length / range);
  return n < 1.0 ? 1 : static_cast<int>(std::min(n, 1.0e5));
}
// Columns of a tilted cell: each at least `range` across its slanted sides, L_x / n * L_y / |b| >= range.
int column_count(const Domain& d, double range) {
  if (d.tilt == 0.0) return cell_count(d.length_x(), range);
  return cell_count(d.length_x() * d.length_y() / std::hypot(d.length_y(), d.tilt), range);
}
}  // namespace

CellGrid::CellGrid(const Domain& domain, double range, const Domain& sizing)
    : nx_(column_count(sizing, range)), ny_(cell_count(sizing.length_y(), range)) {
  follow(domain);
}

void CellGrid::follow(const Domain& domain) {
  domain_ = domain;
  side_x_ = domain.length_x() / nx_;
  side_y_ = domain.length_y() / ny_;
}

double CellGrid::column_width(const Domain& d) const {
  return d.length_x() / nx_ * (d.tilt == 0.0 ? 1.0 : d.length_y() / std::hypot(d.length_y(), d.tilt));
}

std::vector<std::size_t> CellGrid::stencil(std::size_t cell) const {
  const int cx = static_cast<int>(cell % nx_), cy = static_cast<int>(cell / nx_);
  std::vector<std::size_t> out;
  out.reserve(9);
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      int x = cx + dx, y = cy + dy;
      if (domain_.periodic_x) x = (x + nx_) % nx_;
      if (domain_.periodic_y) y = (y + ny_) % ny_;
      if (x < 0 || x >= nx_ || y < 0 || y >= ny_) continue;
      out.push_back(static_cast<std::size_t>(y) * nx_ + x);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace rondel
