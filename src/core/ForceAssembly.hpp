#pragma once
#include <cstdint>
#include <vector>

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
  // Zero forces; body forces (docs/design.md section 4, step 4): force = m g, 0 for fixed discs. (There is no
  // body couple: assemble() starts each torque at 0, so this pass writes the forces only.)
  static void body_forces(DiscStore& discs, Vec2 gravity);
  // Step 6: force = the body force of body_forces() + the contributions, torque = the contributions. Fixed
  // discs then get zero, except that a disc glued to a wall keeps its contact force (no gravity, no torque).
  void assemble(DiscStore& discs, const ContactTable& pairs, const ContactTable& wall_rows) const;

 private:
  enum Side : std::uint8_t { kAsDisc1 = 0, kAsDisc2 = 1, kWall = 2 };
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> row_;
  std::vector<std::uint8_t> side_;
};

}  // namespace rondel
