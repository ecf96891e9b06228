#include "core/NeighbourList.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace rondel {

void NeighbourList::bin(const DiscStore& discs, const Domain& domain, double R_max) {
  grid_ = CellGrid(domain, range(R_max));
  const std::size_t n = discs.size();
  std::vector<int> cx(n), cy(n);
  for (std::size_t i = 0; i < n; ++i)
    cx[i] = grid_.column_of(discs.position[i]), cy[i] = grid_.row_of(discs.position[i].y);
  auto distinct = [](std::vector<int> v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  };
  columns_ = distinct(cx);
  rows_ = distinct(cy);
  const std::size_t n_bins = columns_.size() * rows_.size();
  cell_start_.assign(n_bins + 1, 0);
  std::vector<std::size_t> cell(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell[i] = static_cast<std::size_t>(bin_of(cx[i], cy[i]));
    ++cell_start_[cell[i] + 1];
  }
  for (std::size_t c = 0; c < n_bins; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(n);
  std::vector<std::size_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) cell_items_[fill[cell[i]]++] = i;
}

long NeighbourList::bin_of(int cx, int cy) const {
  const auto x = std::lower_bound(columns_.begin(), columns_.end(), cx);
  const auto y = std::lower_bound(rows_.begin(), rows_.end(), cy);
  if (x == columns_.end() || *x != cx || y == rows_.end() || *y != cy) return -1;
  return static_cast<long>(y - rows_.begin()) * static_cast<long>(columns_.size()) + (x - columns_.begin());
}

std::vector<NeighbourList::Candidate> NeighbourList::candidates(const DiscStore& discs, const Domain& domain,
                                                                std::size_t expected) const {
  if (domain.standing()) return candidates_by(discs, MinimumImage(domain), expected);
  return candidates_by(discs, ShearedImage(domain), expected);
}

template <class Image>
std::vector<NeighbourList::Candidate> NeighbourList::candidates_by(const DiscStore& discs, const Image& image,
                                                                   std::size_t expected) const {
  // About as many as the rows held now: reserved so that the list does not double past its size (the rebuild's
  // peak memory is the old rows, the new rows and this list).
  std::vector<Candidate> found;
  found.reserve(expected + expected / 16 + 64);
  const std::size_t n_owned = discs.n_owned();
  std::vector<std::size_t> around;
  for (std::size_t c = 0; c + 1 < cell_start_.size(); ++c) {
    if (cell_start_[c] == cell_start_[c + 1]) continue;
    around.clear();
    const int column = columns_[c % columns_.size()], row = rows_[c / columns_.size()];
    for (std::size_t g : grid_.stencil(grid_.index(column, row))) {
      const long b = bin_of(static_cast<int>(g % static_cast<std::size_t>(grid_.nx())),
                            static_cast<int>(g / static_cast<std::size_t>(grid_.nx())));
      if (b >= 0) around.push_back(static_cast<std::size_t>(b));
    }
    for (std::size_t a = cell_start_[c]; a < cell_start_[c + 1]; ++a) {
      const std::size_t i = cell_items_[a];
      for (std::size_t c2 : around) {
        for (std::size_t b = cell_start_[c2]; b < cell_start_[c2 + 1]; ++b) {
          const std::size_t j = cell_items_[b];
          if (discs.gid[j] <= discs.gid[i]) continue;  // each pair once, from its lower gid
          if (i >= n_owned && j >= n_owned) continue;
          if (same_rigid_body(discs.flags[i], discs.flags[j])) continue;
          const Vec2 d = image.separation(discs.position[i], discs.position[j]);
          const double reach = discs.radius[i] + discs.radius[j] + skin_;
          if (dot(d, d) < reach * reach)
            found.emplace_back(ContactKey{discs.gid[i], discs.gid[j]}, static_cast<std::int32_t>(i),
                               static_cast<std::int32_t>(j));
        }
      }
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) { return std::get<0>(x) < std::get<0>(y); });
  return found;
}

void NeighbourList::build(const DiscStore& discs, const Domain& domain, WallSet& walls, const ContactParamTable& params,
                          ContactTable& pairs, ContactTable& wall_rows) {
  double R_max = 0.0;
  for (double R : discs.radius) R_max = std::max(R_max, R);
  bin(discs, domain, R_max);
  {
    std::vector<Candidate> found = candidates(discs, domain, pairs.size());
    const ContactTable old_pairs = std::move(pairs);
    pairs = old_pairs.empty_like();
    pairs.reserve(found.size());
    for (const auto& [k, i, j] : found)
      pairs.push(k, i, j, static_cast<std::int32_t>(params.pair_index(discs.material[i], discs.material[j])));
    found = {};  // freed before the history is copied
    pairs.inherit_history(old_pairs);
  }
  build_wall_rows(discs, walls, params, wall_rows);
  position_at_build_.assign(discs.position.begin(), discs.position.begin() + discs.n_owned());
  cell_at_build_ = domain;
  bound_ = 0.0;
  for (auto& w : walls) w.displacement_since_build = {}, w.turn_since_build = 0.0;
  ++builds_;
}

void NeighbourList::build_wall_rows(const DiscStore& discs, const WallSet& walls, const ContactParamTable& params,
                                    ContactTable& wall_rows) const {
  // Every owned disc against every wall, in (gid, wall id) order.
  const std::size_t n_owned = discs.n_owned();
  std::vector<std::size_t> order(n_owned);
  for (std::size_t i = 0; i < n_owned; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return discs.gid[a] < discs.gid[b]; });
  const ContactTable old_walls = std::move(wall_rows);
  wall_rows = old_walls.empty_like();
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
}

double NeighbourList::max_displacement(const DiscStore& discs, const Domain& domain) const {
  if (position_at_build_.size() != discs.n_owned()) return INFINITY;
  double m2 = 0.0;
  if (domain.standing()) {
    const MinimumImage image(domain);
    for (std::size_t i = 0; i < discs.n_owned(); ++i)
      m2 = std::max(m2, squared_displacement(image, position_at_build_[i], discs.position[i]));
  } else {
    // Apart from the affine motion since the build: delta = x - x0 - (F - I)(x0 - corner), by the minimum image.
    const ShearedImage image(domain);
    const Strain G = strain(domain);
    const Vec2 corner = domain.corner();
    for (std::size_t i = 0; i < discs.n_owned(); ++i) {
      const Vec2 x0 = position_at_build_[i];
      const Vec2 d = image.separation(x0 + G.of(x0 - corner), discs.position[i]);
      m2 = std::max(m2, dot(d, d));
    }
  }
  return std::sqrt(m2);
}

NeighbourList::Strain NeighbourList::strain(const Domain& d) const {
  // F = h h0^-1 with h = [[L_x, tilt], [0, L_y]]; G = F - I.
  const Domain& d0 = cell_at_build_;
  const double fx = d.length_x() / d0.length_x();
  return {fx - 1.0, (d.tilt - fx * d0.tilt) / d0.length_y(), d.length_y() / d0.length_y() - 1.0};
}

double NeighbourList::strain_term(const Domain& domain) const {
  if (domain.standing() && cell_at_build_.standing()) return 0.0;
  const Strain G = strain(domain);
  return 0.5 * G.norm() * cell_range_;
}

double NeighbourList::displacement(double max_step, const DiscStore& discs, const Domain& domain,
                                   const WallSet& walls) {
  // In a deforming cell |d delta / dt| <= |v - L (x - x0)| + |L| |delta| (the Frobenius norm bounds |L|).
  if (domain.moving) bound_ *= 1.0 + dt_ * domain.L.norm();
  bound_ += max_step;
  const double affine = strain_term(domain);
  if (!(bound_ + affine <= 0.5 * skin_)) bound_ = max_displacement(discs, domain);  // also a NaN step or position
  double glued = 0.0;
  for (const Wall& w : walls)
    if (w.rough) glued = std::max(glued, std::sqrt(dot(w.displacement_since_build, w.displacement_since_build)));
  return std::max(bound_ + affine, glued);
}

bool NeighbourList::needs_rebuild(double max_disc_disp, const WallSet& walls) const {
  if (!(max_disc_disp <= 0.5 * skin_)) return true;
  double wall_disp = 0.0;
  for (const auto& w : walls) wall_disp = std::max(wall_disp, w.moved_since_build());
  return max_disc_disp + wall_disp > skin_;
}

}  // namespace rondel
