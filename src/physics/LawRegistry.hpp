#pragma once
// The registry of contact laws: one list of law types per kind (LawRows.hpp). Everything that depends
// on the set of laws iterates over it: the kernel selection, the history slots, the critical step's
// springs and the law catalog the configuration layer parses, prints and checks the law blocks with.
#include <boost/program_options.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/Config.hpp"
#include "core/ContactParams.hpp"
#include "core/ContactTable.hpp"
#include "core/ForceAssembly.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactPass.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

// The selected laws by keyword (contact.normal, contact.tangential, contact.rolling), and what the parameter table
// lets the kernel leave out of a rolling law that declares variants (HasKernelVariants, LawConcepts.hpp): where
// every pair and wall is `lean` for it (wang: no rolling dashpot, c_r = 0), its lean Variant, and where moreover
// every one has rolling resistance (ContactParams::rolling), the one without the per-contact test of p.rolling.
// The variants perform the same operations for such tables, so they give the same bits for less work. The
// defaults (false) are right for any parameters.
struct LawSelection {
  std::string normal = "linear";
  std::string tangential = "coulomb";
  std::string rolling = "none";
  bool rolling_lean = false;
  bool rolling_every_row = false;
};
// True when `pred` holds for a pair or a wall of the table.
template <class Pred>
bool any_params(const ContactParamTable& t, Pred pred) {
  for (const std::vector<ContactParams>* rows : {&t.pairs(), &t.walls()})
    for (const ContactParams& p : *rows)
      if (pred(p)) return true;
  return false;
}
// True when every pair and every wall of the table has rolling resistance (ContactParams::rolling).
inline bool every_row_rolls(const ContactParamTable& t) {
  return !any_params(t, [](const ContactParams& p) { return !p.rolling; });
}
// The selection of a configuration, with the flags its parameter table allows.
LawSelection law_selection(const Config& c);

// The catalog's row of each selected law.
const LawInfo& normal_law(const LawSelection& laws);

// The parameters of a contact as the linear spring-dashpot it is at the kinematics `in.k` (the normal law's k_n
// and c_n at this overlap, the tangential law's k_s and zeta_t): the critical step at the largest overlap, the
// servo's stiffest wall contact. The identity for linear laws.
ContactParams linearised(const LawSelection& laws, const ContactInput& in);
// The parameters with the normal law's stiffest spring and its dashpot at the kinematics `in.k`: its unloading
// stiffness where that is stiffer than what the other laws see (walton_braun's K2), else its linearised k_n and c_n.
// The normal mode of the critical step and the servo's gain.
ContactParams stiffest_normal(const LawSelection& laws, const ContactInput& in);

// The kernel and the stored-energy pass instantiated for the selected laws, chosen once at set-up (no
// per-contact dispatch). `run` and `initial` add every row's force and torques to the discs' sums (begun and
// finished by ForceAssembly). `initial` computes the forces of the initial state (a zero increment) without
// committing any history and without booking work: the forces of the first half kick.
struct KernelOps {
  void (*run)(const KernelContext&, ContactTable&, ContactTable&, ForceSums, LedgerStep&) = nullptr;
  void (*initial)(const KernelContext&, ContactTable&, ContactTable&, ForceSums) = nullptr;
  ContactSummary (*stored)(const KernelContext&, ContactTable&, ContactTable&) = nullptr;
};

// Throws ConfigError naming the key for a keyword that no law of its kind has.
KernelOps select_kernel(const LawSelection& laws);
// History slot names of the selected laws, in kernel order (tangential, rolling, then normal).
std::vector<std::string> history_slots(const LawSelection& laws);
// An empty contact table with exactly the columns the selected laws need: of disc-disc rows, or of
// disc-wall rows (wall_rows, with the force column f1).
ContactTable make_contact_table(const LawSelection& laws, bool wall_rows);

// The springs of the selected laws for the critical step of one contact (docs/physics.md section 4); none
// for a law that declares no a-priori spring, and no rolling spring where p.rolling is false.
std::optional<TangentialSpring> tangential_spring(const LawSelection& laws, const ContactParams& p);
std::optional<RollingSpring> rolling_spring(const LawSelection& laws, const ContactParams& p, const ContactBodies& b,
                                            const ContactKinematics& geometry);

// Every law of every kind, as the configuration layer sees it.
const LawCatalog& law_catalog();

// The configuration entry points with the registry's catalog (core/Config.hpp takes it as an argument
// because core may not include physics).
Config parse_config(int argc, const char* const* argv);
Config parse_config_text(const std::string& ini, const std::vector<std::string>& overrides = {});
std::string config_help();
boost::program_options::options_description config_schema();

}  // namespace rondel
