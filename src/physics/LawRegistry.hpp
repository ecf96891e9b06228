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

// The kernel and the stored-energy pass instantiated for the selected laws, chosen once at set-up (no
// per-contact dispatch).
struct KernelOps {
  void (*run)(const KernelContext&, ContactTable&, ContactTable&, LedgerStep&) = nullptr;
  ContactSummary (*stored)(const KernelContext&, ContactTable&, ContactTable&) = nullptr;
};

KernelOps select_kernel(const LawSelection& laws);
// History slot names of the selected laws, in kernel order (tangential, then rolling).
std::vector<std::string> history_slots(const LawSelection& laws);
// An empty contact table with exactly the columns the selected laws need.
ContactTable make_contact_table(const LawSelection& laws);

// Keyword <-> law. parse_* return false for an unknown keyword.
bool parse_rolling_law(const std::string& name, RollingLaw& out);
// Every rolling keyword, "none" first, separated by " | " (for messages and --help).
std::string rolling_law_names();

}  // namespace rondel
