#pragma once
// Body forces that a script sets on some discs by gid (the Python driver, docs/python.md), beside gravity. The list
// is the script's (held alike on every rank, as long as the script made it), applied to this rank's owned discs
// after the contact kernel, so a disc's force sum is the same on any rank count: gravity, the contacts in the
// kernel's order, then this force. A force set between steps enters the sums of the next opening kick at once (as
// if it had been summed with them), so it acts from the next step on and one that cancels gravity holds a disc
// exactly. Its work over a step is booked as W_driver with the drift's half-step velocity, (F_before + F_now) / 2 .
// dt v (the force of the last closing kick and of this one), as gravity's is. Not in checkpoints: a resumed script
// sets its forces again. A scene without them pays one test per step.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/DiscStore.hpp"

namespace rondel {

class DriverForces {
 public:
  bool empty() const { return entries_.empty(); }
  std::size_t size() const { return entries_.size(); }
  // Sets (replaces) the forces of `gids` [N] and changes the owned discs' sums of the next opening kick by the
  // difference (`discs` between steps); a zero force ends one after the next step.
  void set(const std::vector<std::int64_t>& gids, const std::vector<Vec2>& forces, DiscStore& discs);
  // The owned discs of the entries, after their indices changed (a rebuild) or the list did.
  void locate(const DiscStore& discs);
  // Adds each force to its owned, free disc's force sum; returns the work of this step on this rank.
  double apply(DiscStore& discs, double dt);
  // The force set on `gid` (0 when none).
  Vec2 of(std::int64_t gid) const;

 private:
  struct Entry {
    std::int64_t gid = 0;
    Vec2 force, before;         // now, and in the last step's closing kick
    std::ptrdiff_t index = -1;  // the owned disc (-1: another rank's)
  };
  std::vector<Entry> entries_;  // ascending gid
};

}  // namespace rondel
