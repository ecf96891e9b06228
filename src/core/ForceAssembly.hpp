#pragma once
#include <cstdint>
#include <vector>

#include "core/BodyForce.hpp"
#include "core/DiscStore.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// Where the contact kernel adds each row's force and torques: the discs' sums, indexed by local disc (owned
// discs and ghosts; a ghost's entries are scratch that nothing reads).
struct ForceSums {
  Vec2* force;
  double* torque;
  static ForceSums of(DiscStore& discs) { return {discs.force.data(), discs.torque.data()}; }
};

// Each owned disc's force and torque are summed in a fixed order: the body force, then its contact terms in
// ascending partner gid, then its walls by wall id (docs/design.md sections 4 and 5, step 6). The contact
// kernel adds the contact terms in that order as it goes (rows are in ascending key order,
// physics/ContactKernel.hpp); this class starts the sums and finishes them, so the result does not depend
// on storage order, rank count or when the list was rebuilt.
class ForceAssembly {
 public:
  // Once per neighbour-list build: remembers the owned fixed discs (their sums are finished specially).
  void build(const DiscStore& discs);
  // Before the kernel: force = the body force (step 4, the first term of each sum), torque = 0, for every
  // owned disc; the ghosts' entries zero.
  static void begin(DiscStore& discs, const BodyForce& body);
  // The same after the step's drift, which starts the free discs' sums itself (Integrator::half_kick_drift):
  // the fixed discs' sums (no body force on them) and the ghosts' entries.
  void begin_fixed_and_ghosts(DiscStore& discs) const;
  // After the kernel: a fixed disc does not move under its load, so it gets zero force and torque, except
  // that a disc glued to a wall keeps its contact force (the reaction the wall carries, used by the energy
  // ledger), without gravity.
  void finish(DiscStore& discs) const;

 private:
  std::vector<std::uint32_t> fixed_;  // the owned fixed discs
};

}  // namespace rondel
