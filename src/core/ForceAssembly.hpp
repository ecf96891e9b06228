#pragma once
#include <cstdint>
#include <vector>

#include "core/BodyForce.hpp"
#include "core/ContactTable.hpp"
#include "core/DiscStore.hpp"
#include "core/Vec2.hpp"

namespace rondel {

// Sums each owned disc's contact contributions in a fixed order: ascending partner gid, then walls by
// wall id (docs/design.md section 4, step 6). The order is built once per neighbour-list build, so the sum does
// not depend on storage order, rank count or when the list was rebuilt.
class ForceAssembly {
 public:
  void build(const DiscStore& discs, const ContactTable& pairs, const ContactTable& wall_rows);
  // Step 6: force = the body force (step 4, the first term of the sum) + the contributions, torque = the
  // contributions. Fixed discs then get zero, except that a disc glued to a wall keeps its contact force (no
  // gravity, no torque). The body force enters here rather than in a pass of its own: at 160,000 discs a
  // separate pass writing every force and reading it back cost 7 % of the benchmark's step.
  void assemble(DiscStore& discs, const BodyForce& body, const ContactTable& pairs,
                const ContactTable& wall_rows) const;

 private:
  enum Side : std::uint8_t { kAsDisc1 = 0, kAsDisc2 = 1, kWall = 2 };
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> row_;
  std::vector<std::uint8_t> side_;
};

}  // namespace rondel
