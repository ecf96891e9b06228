#pragma once
// The `none` rolling law: no history column, no rolling arithmetic (the kernel drops every rolling term
// at compile time when kActive is false).
#include <array>
#include <cmath>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

struct RollingNone {
  static constexpr const char* name = "none";
  static constexpr const LawBlock* block = nullptr;
  static constexpr const char* no_spring = "no rolling resistance";
  static constexpr bool kActive = false;
  static constexpr std::array<const char*, 0> slots{};
  struct History {};
  static RollingCouple moment(const ContactInput&, History) { return {}; }
  static double stored(const ContactInput&, History) { return 0.0; }
  static double cap(const ContactInput&) { return INFINITY; }
};

}  // namespace rondel
