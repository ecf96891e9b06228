#pragma once
#include <cstdint>

#include "core/DiscStore.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// The body force of the time step (docs/architecture.md, step 4): gravity, m g on every free disc and nothing
// on fixed ones (a disc glued to a wall carries no weight of its own; no body couple). It is the first term of
// each disc's force sum (ForceAssembly::assemble), so it costs no pass over the discs of its own; the
// drift books its work (Integrator::half_kick_drift).
struct BodyForce {
  Vec2 gravity;
  Vec2 on(double mass, std::uint32_t flags) const { return (flags & kFlagFixed) ? Vec2{} : mass * gravity; }
};

}  // namespace rondel
