#include "core/NeighbourList.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rondel {

void NeighbourList::bin(const DiscStore& discs, const Domain& domain, double R_max) {
  grid_ = CellGrid(domain, range(R_max));
  const std::size_t n_cells = grid_.size();
  cell_start_.assign(n_cells + 1, 0);
  std::vector<std::size_t> cell(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i) {
    cell[i] = grid_.cell_of(discs.position[i]);
    ++cell_start_[cell[i] + 1];
  }
  for (std::size_t c = 0; c < n_cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(discs.size());
  std::vector<std::size_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < discs.size(); ++i) cell_items_[fill[cell[i]]++] = i;
}

void NeighbourList::build(const DiscStore& discs, const Domain& domain, WallSet& walls, const ContactParamTable& params,
                          const ContactTable& old_pairs, ContactTable& pairs, const ContactTable& old_walls,
                          ContactTable& wall_rows) {
  double R_max = 0.0;
  for (double R : discs.radius) R_max = std::max(R_max, R);
  bin(discs, domain, R_max);
  const std::size_t n_owned = discs.n_owned();

  std::vector<std::tuple<ContactKey, std::int32_t, std::int32_t>> found;
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) {
    const auto around = grid_.stencil(c);
    for (std::size_t a = cell_start_[c]; a < cell_start_[c + 1]; ++a) {
      const std::size_t i = cell_items_[a];
      for (std::size_t c2 : around) {
        for (std::size_t b = cell_start_[c2]; b < cell_start_[c2 + 1]; ++b) {
          const std::size_t j = cell_items_[b];
          if (discs.gid[j] <= discs.gid[i]) continue;  // each pair once, from its lower gid
          if (i >= n_owned && j >= n_owned) continue;
          if (same_rigid_body(discs.flags[i], discs.flags[j])) continue;
          const Vec2 d = domain.separation(discs.position[i], discs.position[j]);
          const double reach = discs.radius[i] + discs.radius[j] + skin_;
          if (dot(d, d) < reach * reach)
            found.emplace_back(ContactKey{discs.gid[i], discs.gid[j]}, static_cast<std::int32_t>(i),
                               static_cast<std::int32_t>(j));
        }
      }
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
  pairs.clear();
  for (const auto& [k, i, j] : found)
    pairs.push(k, i, j, static_cast<std::int32_t>(params.pair_index(discs.material[i], discs.material[j])));
  pairs.inherit_history(old_pairs);

  // Wall rows: every owned disc against every wall, in (gid, wall id) order.
  std::vector<std::size_t> order(n_owned);
  for (std::size_t i = 0; i < n_owned; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return discs.gid[a] < discs.gid[b]; });
  wall_rows.clear();
  for (std::size_t i : order) {
    if (is_attached(discs.flags[i])) continue;  // a glued disc is part of a wall: walls do not meet walls
    for (std::size_t w = 0; w < walls.size(); ++w) {
      if (walls[w].proximity(discs.position[i]).dist < discs.radius[i] + skin_)
        wall_rows.push({discs.gid[i], static_cast<std::int64_t>(w)}, static_cast<std::int32_t>(i),
                       static_cast<std::int32_t>(w),
                       static_cast<std::int32_t>(params.wall_index(discs.material[i], walls[w].material)));
    }
  }
  wall_rows.inherit_history(old_walls);

  position_at_build_.assign(discs.position.begin(), discs.position.begin() + n_owned);
  for (auto& w : walls) w.displacement_since_build = {};
  ++builds_;
}

double NeighbourList::max_displacement(const DiscStore& discs, const Domain& domain) const {
  if (position_at_build_.size() != discs.n_owned()) return INFINITY;
  double m2 = 0.0;
  for (std::size_t i = 0; i < discs.n_owned(); ++i) {
    const Vec2 d = domain.separation(position_at_build_[i], discs.position[i]);
    m2 = std::max(m2, dot(d, d));
  }
  return std::sqrt(m2);
}

bool NeighbourList::needs_rebuild(double max_disc_disp, const WallSet& walls) const {
  if (!(max_disc_disp <= 0.5 * skin_)) return true;
  double wall_disp = 0.0;
  for (const auto& w : walls)
    wall_disp = std::max(wall_disp, std::sqrt(dot(w.displacement_since_build, w.displacement_since_build)));
  return max_disc_disp + wall_disp > skin_;
}

}  // namespace rondel
