#pragma once
#include <string>
#include <vector>

#include "core/ContactTable.hpp"
#include "physics/ContactKernel.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

struct LawSelection {
  NormalLaw normal = NormalLaw::linear;
  TangentialLaw tangential = TangentialLaw::coulomb;
  RollingLaw rolling = RollingLaw::none;
};

using KernelFn = void (*)(const KernelContext&, ContactTable&, ContactTable&, LedgerStep&);

// The kernel instantiated for the selected laws, chosen once at set-up (no per-contact dispatch).
KernelFn select_kernel(const LawSelection& laws);
// History slot names of the selected laws, in kernel order (tangential, then rolling).
std::vector<std::string> history_slots(const LawSelection& laws);
// An empty contact table with exactly the columns the selected laws need.
ContactTable make_contact_table(const LawSelection& laws);

}  // namespace rondel
