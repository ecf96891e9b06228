#include "parallel/Partitioner.hpp"

#include <metis.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <tuple>

#include "core/Errors.hpp"

namespace rondel {

std::pair<int, int> grid_blocks(const CellGrid& grid, int ranks) {
  // The factorisation px x py = ranks whose blocks are closest to square (in cells).
  int best_px = 1;
  double best = INFINITY;
  for (int px = 1; px <= ranks; ++px) {
    if (ranks % px != 0) continue;
    const int py = ranks / px;
    if (px > grid.nx() || py > grid.ny()) continue;
    const double aspect =
        std::fabs(std::log((static_cast<double>(grid.nx()) / px) / (static_cast<double>(grid.ny()) / py)));
    if (aspect < best) best = aspect, best_px = px;
  }
  if (!std::isfinite(best))
    throw ConfigError("parallel.partitioner = grid: " + std::to_string(ranks) +
                      " ranks cannot be laid out in blocks of the " + std::to_string(grid.nx()) + " x " +
                      std::to_string(grid.ny()) + " cell grid; use fewer ranks or parallel.partitioner = metis");
  return {best_px, ranks / best_px};
}

int grid_block_of(const CellGrid& grid, std::pair<int, int> blocks, int cx, int cy) {
  const int bx = static_cast<int>(static_cast<long>(cx) * blocks.first / grid.nx());
  const int by = static_cast<int>(static_cast<long>(cy) * blocks.second / grid.ny());
  return by * blocks.first + bx;
}

std::vector<int> grid_partition(const CellGrid& grid, int ranks) {
  const auto blocks = grid_blocks(grid, ranks);
  std::vector<int> map(grid.size());
  for (int cy = 0; cy < grid.ny(); ++cy)
    for (int cx = 0; cx < grid.nx(); ++cx) map[grid.index(cx, cy)] = grid_block_of(grid, blocks, cx, cy);
  return map;
}

std::vector<int> relabel_parts(const std::vector<int>& parts, const std::vector<int>& previous,
                               const std::vector<long>& weights, int ranks) {
  if (previous.size() != parts.size()) return parts;
  std::vector<long> overlap(static_cast<std::size_t>(ranks) * ranks, 0);
  for (std::size_t c = 0; c < parts.size(); ++c)
    overlap[static_cast<std::size_t>(parts[c]) * ranks + previous[c]] += weights[c];
  std::vector<std::tuple<long, int, int>> order;  // (-overlap, part, rank)
  for (int p = 0; p < ranks; ++p)
    for (int r = 0; r < ranks; ++r) order.emplace_back(-overlap[static_cast<std::size_t>(p) * ranks + r], p, r);
  std::sort(order.begin(), order.end());
  std::vector<int> label(ranks, -1);
  std::vector<bool> taken(ranks, false);
  for (const auto& [neg, p, r] : order) {
    if (label[p] >= 0 || taken[r]) continue;
    label[p] = r;
    taken[r] = true;
  }
  std::vector<int> out(parts.size());
  for (std::size_t c = 0; c < parts.size(); ++c) out[c] = label[parts[c]];
  return out;
}

std::vector<int> metis_partition(const CellGrid& grid, int ranks, const std::vector<long>& weights,
                                 const std::vector<int>& previous) {
  if (ranks == 1) return std::vector<int>(grid.size(), 0);
  idx_t n = static_cast<idx_t>(grid.size());
  std::vector<idx_t> xadj{0}, adjncy, vwgt(grid.size());
  for (std::size_t c = 0; c < grid.size(); ++c) {
    for (std::size_t nb : grid.stencil(c))
      if (nb != c) adjncy.push_back(static_cast<idx_t>(nb));
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    vwgt[c] = static_cast<idx_t>(std::min<long>(weights[c], 1L << 30));
  }
  idx_t ncon = 1, nparts = ranks, objval = 0;
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 20151;
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_UFACTOR] = 10;  // allowed load imbalance 1.01
  std::vector<idx_t> part(grid.size());
  const int status = METIS_PartGraphKway(&n, &ncon, xadj.data(), adjncy.data(), vwgt.data(), nullptr, nullptr, &nparts,
                                         nullptr, nullptr, options, &objval, part.data());
  if (status != METIS_OK) throw std::runtime_error("METIS_PartGraphKway failed with status " + std::to_string(status));
  std::vector<int> parts(part.begin(), part.end());
  return relabel_parts(parts, previous, weights, ranks);
}

}  // namespace rondel
