#include "core/NeighbourList.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace rondel {

void NeighbourList::bin(const DiscStore& discs, const Domain& domain, double R_max) {
  grid_ = CellGrid(domain, range(R_max));
  const std::size_t n = discs.size();
  if (n >= UINT32_MAX) throw std::length_error("a neighbour list of 2^32 discs or more on one rank");
  std::vector<int> cx(n), cy(n);
  for (std::size_t i = 0; i < n; ++i)
    cx[i] = grid_.column_of(discs.position[i]), cy[i] = grid_.row_of(discs.position[i].y);
  // The distinct values of v, ascending, and each one's place among them by value over their span: marked over
  // the span when it is not much wider than v (a rank's compact region), else sorted and found by binary search
  // (a periodic wrap's far side; `slot` empty).
  const auto compress = [](std::vector<int> v, std::vector<int>& slot) {
    slot.clear();
    if (v.empty()) return v;
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const int first = *lo;
    const auto span = static_cast<std::size_t>(*hi - first) + 1;
    if (span > 4 * v.size() + 64) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
      return v;
    }
    slot.assign(span, -1);
    for (int c : v) slot[static_cast<std::size_t>(c - first)] = 0;
    v.clear();
    for (std::size_t k = 0; k < span; ++k)
      if (slot[k] == 0) slot[k] = static_cast<int>(v.size()), v.push_back(first + static_cast<int>(k));
    return v;
  };
  columns_ = compress(cx, column_slot_);
  rows_ = compress(cy, row_slot_);
  const std::size_t n_bins = columns_.size() * rows_.size();
  cell_start_.assign(n_bins + 1, 0);
  std::vector<std::size_t> cell(n);
  for (std::size_t i = 0; i < n; ++i) {
    cell[i] = static_cast<std::size_t>(bin_of(cx[i], cy[i]));
    ++cell_start_[cell[i] + 1];
  }
  for (std::size_t c = 0; c < n_bins; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_items_.resize(n);
  std::vector<std::uint32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) cell_items_[fill[cell[i]]++] = static_cast<std::uint32_t>(i);
}

namespace {
// The place of c among the ascending `values` (-1: not there), by `slot` over their span when there is one.
long place(const std::vector<int>& values, const std::vector<int>& slot, int c) {
  if (values.empty()) return -1;
  if (!slot.empty()) {
    const long k = static_cast<long>(c) - values.front();
    return k >= 0 && k < static_cast<long>(slot.size()) ? slot[static_cast<std::size_t>(k)] : -1;
  }
  const auto at = std::lower_bound(values.begin(), values.end(), c);
  return at == values.end() || *at != c ? -1 : static_cast<long>(at - values.begin());
}

// Disc a before disc b: by gid, then by index (a ghost's periodic images share its gid).
bool gid_less(const DiscStore& discs, std::uint32_t a, std::uint32_t b) {
  return discs.gid[a] < discs.gid[b] || (discs.gid[a] == discs.gid[b] && a < b);
}

// The discs [from, to) in gid order (ties by index), or none when they are in it already (`sorted_ok`): the owned
// discs are after every migration.
std::vector<std::uint32_t> by_gid_order(const DiscStore& discs, std::size_t from, std::size_t to, bool sorted_ok) {
  const auto first = discs.gid.begin() + static_cast<std::ptrdiff_t>(from);
  if (sorted_ok && std::is_sorted(first, discs.gid.begin() + static_cast<std::ptrdiff_t>(to))) return {};
  std::vector<std::uint32_t> out(to - from);
  for (std::size_t k = 0; k < out.size(); ++k) out[k] = static_cast<std::uint32_t>(from + k);
  std::sort(out.begin(), out.end(), [&discs](std::uint32_t a, std::uint32_t b) { return gid_less(discs, a, b); });
  return out;
}
}  // namespace

long NeighbourList::bin_of(int cx, int cy) const {
  const long x = place(columns_, column_slot_, cx), y = place(rows_, row_slot_, cy);
  if (x < 0 || y < 0) return -1;
  return y * static_cast<long>(columns_.size()) + x;
}

std::vector<RowCandidate> NeighbourList::candidates(const DiscStore& discs, const Domain& domain,
                                                    std::size_t expected) const {
  if (domain.standing()) return candidates_by(discs, MinimumImage(domain), expected);
  return candidates_by(discs, ShearedImage(domain), expected);
}

template <class Image>
std::vector<RowCandidate> NeighbourList::candidates_by(const DiscStore& discs, const Image& image,
                                                       std::size_t expected) const {
  // About as many as the rows held now: reserved so that the list does not double past its size (the rebuild's
  // peak memory is the kept columns of the old rows, this list and the new keys: ContactTable::replace_rows).
  // The rows come out in ascending key with no sort of the list: the discs are visited in gid order (the owned
  // ones are in it after every migration, the few ghosts are sorted here) and each one's partners of higher gid
  // in gid order.
  std::vector<RowCandidate> found;
  found.reserve(expected + expected / 16 + 64);
  const std::size_t n = discs.size(), n_owned = discs.n_owned();
  const auto by_gid = [&discs](std::uint32_t a, std::uint32_t b) { return gid_less(discs, a, b); };
  const std::vector<std::uint32_t> ghosts = by_gid_order(discs, n_owned, n, false);
  const std::vector<std::uint32_t> owned = by_gid_order(discs, 0, n_owned, true);  // empty: 0, 1, ... in gid order
  std::vector<std::size_t> around;
  std::vector<std::uint32_t> partners;
  const auto rows_of = [&](std::size_t i) {
    around.clear();
    grid_.for_each_in_stencil(grid_.cell_of(discs.position[i]), [&](int x, int y) {
      const long b = bin_of(x, y);
      if (b >= 0) around.push_back(static_cast<std::size_t>(b));
    });
    std::sort(around.begin(), around.end());  // each bin once (a periodic grid of one or two cells across)
    around.erase(std::unique(around.begin(), around.end()), around.end());
    partners.clear();
    for (std::size_t c2 : around) {
      for (std::size_t b = cell_start_[c2]; b < cell_start_[c2 + 1]; ++b) {
        const std::size_t j = cell_items_[b];
        if (discs.gid[j] <= discs.gid[i]) continue;  // each pair once, from its lower gid
        if (i >= n_owned && j >= n_owned) continue;
        if (same_rigid_body(discs.flags[i], discs.flags[j])) continue;
        const Vec2 d = image.separation(discs.position[i], discs.position[j]);
        const double reach = discs.radius[i] + discs.radius[j] + skin_;
        if (dot(d, d) < reach * reach) partners.push_back(static_cast<std::uint32_t>(j));
      }
    }
    std::sort(partners.begin(), partners.end(), by_gid);
    for (std::uint32_t j : partners)
      found.push_back(
          {ContactKey{discs.gid[i], discs.gid[j]}, static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
  };
  std::size_t g = 0;  // the owned discs and the ghosts merged by gid
  for (std::size_t k = 0; k < n_owned; ++k) {
    const std::uint32_t i = owned.empty() ? static_cast<std::uint32_t>(k) : owned[k];
    for (; g < ghosts.size() && by_gid(ghosts[g], i); ++g) rows_of(ghosts[g]);
    rows_of(i);
  }
  for (; g < ghosts.size(); ++g) rows_of(ghosts[g]);
  return found;
}

void NeighbourList::build(const DiscStore& discs, const Domain& domain, WallSet& walls, const ContactParamTable& params,
                          ContactTable& pairs, ContactTable& wall_rows) {
  double R_max = 0.0;
  for (double R : discs.radius) R_max = std::max(R_max, R);
  bin(discs, domain, R_max);
  {
    std::vector<RowCandidate> found = candidates(discs, domain, pairs.size());
    pairs.replace_rows(found);
    for (std::size_t r = 0; r < pairs.size(); ++r)
      pairs.param[r] =
          static_cast<std::int32_t>(params.pair_index(discs.material[pairs.i1[r]], discs.material[pairs.i2[r]]));
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
  // Every owned disc against every wall, in (gid, wall id) order (the owned discs are in gid order after a
  // migration; an order of indices only when they are not). No wall: no row, and no pass over the discs.
  const ContactTable old_walls = std::move(wall_rows);
  wall_rows = old_walls.empty_like();
  if (walls.empty()) return;
  const std::size_t n_owned = discs.n_owned();
  const std::vector<std::uint32_t> order = by_gid_order(discs, 0, n_owned, true);
  for (std::size_t k = 0; k < n_owned; ++k) {
    const std::size_t i = order.empty() ? k : order[k];
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
