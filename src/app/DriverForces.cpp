#include "app/DriverForces.hpp"

#include <algorithm>

namespace rondel {

void DriverForces::set(const std::vector<std::int64_t>& gids, const std::vector<Vec2>& forces, DiscStore& discs) {
  const auto find = [this](std::int64_t gid) {
    return std::lower_bound(entries_.begin(), entries_.end(), gid,
                            [](const Entry& e, std::int64_t g) { return e.gid < g; });
  };
  std::vector<Vec2> change(gids.size());
  for (std::size_t k = 0; k < gids.size(); ++k) {
    auto at = find(gids[k]);
    if (at == entries_.end() || at->gid != gids[k]) at = entries_.insert(at, Entry{gids[k], Vec2{}, Vec2{}, -1});
    change[k] = forces[k] - at->force;
    at->force = at->before = forces[k];
  }
  locate(discs);
  // The state between steps holds the sums of the next opening kick: they take the change now, so that the force
  // acts from that kick on, as if it had been summed with them.
  for (std::size_t k = 0; k < gids.size(); ++k) {
    const std::ptrdiff_t i = find(gids[k])->index;
    if (i >= 0 && !(discs.flags[static_cast<std::size_t>(i)] & kFlagFixed))
      discs.force[static_cast<std::size_t>(i)] += change[k];
  }
}

void DriverForces::locate(const DiscStore& discs) {
  const auto first = discs.gid.begin(), last = first + static_cast<std::ptrdiff_t>(discs.n_owned());
  const bool in_order = std::is_sorted(first, last);  // Simulation::rebuild keeps the owned discs in gid order
  for (Entry& e : entries_) {
    const auto at = in_order ? std::lower_bound(first, last, e.gid) : std::find(first, last, e.gid);
    e.index = (at != last && *at == e.gid) ? at - first : -1;
  }
}

double DriverForces::apply(DiscStore& discs, double dt) {
  double work = 0.0;
  // `before` is kept alike on every rank (the force of the list, whoever owns the disc), so that a disc that
  // migrated books its work as it would have stayed; a fixed disc is at rest and books none.
  for (Entry& e : entries_) {
    if (e.index >= 0) {
      const auto i = static_cast<std::size_t>(e.index);
      work += 0.5 * dot(e.before + e.force, dt * discs.velocity[i]);
      if (!(discs.flags[i] & kFlagFixed)) discs.force[i] += e.force;
    }
    e.before = e.force;
  }
  // A force set to zero has acted in its last kick: its entry goes.
  entries_.erase(std::remove_if(entries_.begin(), entries_.end(),
                                [](const Entry& e) {
                                  return e.force.x == 0.0 && e.force.y == 0.0 && e.before.x == 0.0 && e.before.y == 0.0;
                                }),
                 entries_.end());
  return work;
}

Vec2 DriverForces::of(std::int64_t gid) const {
  const auto at =
      std::lower_bound(entries_.begin(), entries_.end(), gid, [](const Entry& e, std::int64_t g) { return e.gid < g; });
  return at != entries_.end() && at->gid == gid ? at->force : Vec2{};
}

}  // namespace rondel
