#include "core/ForceAssembly.hpp"

#include <algorithm>
#include <tuple>

namespace rondel {

void ForceAssembly::build(const DiscStore& discs, const ContactTable& pairs, const ContactTable& wall_rows) {
  const std::size_t n = discs.n_owned();
  std::vector<std::uint32_t> count(n + 1, 0);
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    if (static_cast<std::size_t>(pairs.i1[r]) < n) ++count[pairs.i1[r] + 1];
    if (static_cast<std::size_t>(pairs.i2[r]) < n) ++count[pairs.i2[r] + 1];
  }
  for (std::size_t r = 0; r < wall_rows.size(); ++r) ++count[wall_rows.i1[r] + 1];
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  start_ = count;

  // (kind, partner, row, side) per entry; kind 0 = disc partner, 1 = wall.
  using Entry = std::tuple<int, std::int64_t, std::uint32_t, std::uint8_t>;
  std::vector<Entry> entries(start_[n]);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t r = 0; r < pairs.size(); ++r) {
    const auto a = static_cast<std::size_t>(pairs.i1[r]);
    const auto b = static_cast<std::size_t>(pairs.i2[r]);
    if (a < n) entries[fill[a]++] = {0, pairs.key[r].hi, static_cast<std::uint32_t>(r), kAsDisc1};
    if (b < n) entries[fill[b]++] = {0, pairs.key[r].lo, static_cast<std::uint32_t>(r), kAsDisc2};
  }
  for (std::size_t r = 0; r < wall_rows.size(); ++r) {
    const auto a = static_cast<std::size_t>(wall_rows.i1[r]);
    entries[fill[a]++] = {1, wall_rows.key[r].hi, static_cast<std::uint32_t>(r), kWall};
  }
  row_.resize(entries.size());
  side_.resize(entries.size());
  for (std::size_t i = 0; i < n; ++i) {
    std::sort(entries.begin() + start_[i], entries.begin() + start_[i + 1]);
    for (std::uint32_t e = start_[i]; e < start_[i + 1]; ++e) {
      row_[e] = std::get<2>(entries[e]);
      side_[e] = std::get<3>(entries[e]);
    }
  }
}

void ForceAssembly::assemble(DiscStore& discs, const BodyForce& body, const ContactTable& pairs,
                             const ContactTable& wall_rows) const {
  const std::size_t n = discs.n_owned();
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint32_t flags = discs.flags[i];
    Vec2 F = body.on(discs.mass[i], flags);  // the body force comes first in the sum
    double T = 0.0;                          // no body couple
    for (std::uint32_t e = start_[i]; e < start_[i + 1]; ++e) {
      const std::uint32_t r = row_[e];
      switch (side_[e]) {
        case kAsDisc1:
          F += pairs.f1[r];
          T += pairs.tq1[r];
          break;
        case kAsDisc2:
          F -= pairs.f1[r];
          T += pairs.tq2[r];
          break;
        default:
          F += wall_rows.f1[r];
          T += wall_rows.tq1[r];
          break;
      }
    }
    if (flags & kFlagFixed) {
      // A fixed disc does not move under its load; a disc glued to a wall keeps its contact force (the
      // reaction the wall carries, used by the energy ledger), without gravity.
      if (!is_attached(flags)) F = {};
      T = 0.0;
    }
    discs.force[i] = F;
    discs.torque[i] = T;
  }
}

}  // namespace rondel
