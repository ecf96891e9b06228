#include "core/ForceAssembly.hpp"

#include <algorithm>

namespace rondel {

void ForceAssembly::build(const DiscStore& discs) {
  fixed_.clear();
  for (std::size_t i = 0; i < discs.n_owned(); ++i)
    if (discs.flags[i] & kFlagFixed) fixed_.push_back(static_cast<std::uint32_t>(i));
}

void ForceAssembly::begin(DiscStore& discs, const BodyForce& body) {
  const std::size_t n = discs.n_owned();
  for (std::size_t i = 0; i < n; ++i) {
    discs.force[i] = body.on(discs.mass[i], discs.flags[i]);  // the body force comes first in the sum
    discs.torque[i] = 0.0;                                    // no body couple
  }
  std::fill(discs.force.begin() + static_cast<std::ptrdiff_t>(n), discs.force.end(), Vec2{});
  std::fill(discs.torque.begin() + static_cast<std::ptrdiff_t>(n), discs.torque.end(), 0.0);
}

void ForceAssembly::begin_fixed_and_ghosts(DiscStore& discs) const {
  for (std::uint32_t i : fixed_) {
    discs.force[i] = {};  // BodyForce::on of a fixed disc
    discs.torque[i] = 0.0;
  }
  const auto n = static_cast<std::ptrdiff_t>(discs.n_owned());
  std::fill(discs.force.begin() + n, discs.force.end(), Vec2{});
  std::fill(discs.torque.begin() + n, discs.torque.end(), 0.0);
}

void ForceAssembly::finish(DiscStore& discs) const {
  for (std::uint32_t i : fixed_) {
    if (!is_attached(discs.flags[i])) discs.force[i] = {};
    discs.torque[i] = 0.0;
  }
}

}  // namespace rondel
