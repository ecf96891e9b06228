// The registry's functions over the rows of LawRows.hpp. Every (linear, tangential, rolling) combination of
// the step kernel is instantiated here, once; those of the other normal laws in NormalLawKernels.cpp.
#include "physics/LawRegistry.hpp"

#include <type_traits>

#include "core/ConfigSchema.hpp"
#include "physics/BondParallel.hpp"
#include "physics/LawRows.hpp"

namespace rondel {

using registry::NormalLaws;
using registry::RollingLaws;
using registry::TangentialLaws;
using registry::with_laws;

const LawCatalog& law_catalog() {
  static const LawCatalog catalog{NormalLaws::kind("normal"), TangentialLaws::kind("tangential"),
                                  RollingLaws::kind("rolling"), &kBondBlock};
  return catalog;
}

KernelOps select_kernel(const LawSelection& laws) {
  KernelOps ops;
  if (laws.normal != NormalLaws::First::name)
    ops = registry::select_normal_law_kernel(laws);
  else  // the kernels of the default normal law only, here (LawRows.hpp, select_normal_law_kernel)
    registry::with_kernel_laws(laws, [&]<class N, class T, class R>() {
      if constexpr (std::is_same_v<N, NormalLaws::First> && registry::compatible<N, T>()) {
        using K = ContactKernel<N, T, R>;
        ops = KernelOps{&K::run, registry::select_initial_forces(laws), &K::stored_energy};
      }
    });
  if (!ops.run)
    throw ConfigError("contact.tangential = " + laws.tangential +
                      " needs contact.normal = " + law_catalog().tangential.find(laws.tangential)->needs_normal);
  return ops;
}

const LawInfo& normal_law(const LawSelection& laws) {
  const LawInfo* law = law_catalog().normal.find(laws.normal);
  if (!law) registry::unknown(law_catalog().normal, laws.normal);
  return *law;
}

LawSelection law_selection(const Config& c) {
  LawSelection laws{c.normal_law, c.tangential_law, c.rolling_law};
  with_laws(laws, [&]<class T, class R>() {
    if constexpr (HasKernelVariants<R>)
      laws.rolling_lean = !any_params(c.params, [](const ContactParams& p) { return !R::lean(p); });
  });
  laws.rolling_every_row = every_row_rolls(c.params);
  return laws;
}

ContactParams stiffest_normal(const LawSelection& laws, const ContactInput& in) {
  ContactParams q = in.p;
  NormalLaws::with(normal_law(laws).keyword, [&]<class N>() { q = stiffest_normal<N>(in); });
  return q;
}

ContactParams linearised(const LawSelection& laws, const ContactInput& in) {
  ContactParams q = in.p;
  registry::NormalLaws::with(laws.normal, [&]<class N>() { q = N::linearised(in); });
  with_laws(laws, [&]<class T, class R>() {
    const ContactParams t = linearised_tangential<T>(in);
    q.k_s = t.k_s, q.zeta_t = t.zeta_t;
  });
  return q;
}

std::vector<std::string> history_slots(const LawSelection& laws) {
  std::vector<std::string> out;
  with_laws(laws, [&out]<class T, class R>() {
    for (const char* s : T::slots) out.emplace_back(s);
    for (const char* s : R::slots) out.emplace_back(s);
  });
  NormalLaws::with(normal_law(laws).keyword, [&out]<class N>() {
    for (const char* s : N::slots) out.emplace_back(s);
  });
  return out;
}

ContactTable make_contact_table(const LawSelection& laws, bool wall_rows) {
  int couples = 0;
  with_laws(laws, [&couples]<class T, class R>() { couples = couple_columns<R>(); });
  return ContactTable(history_slots(laws), couples, wall_rows);
}

std::optional<TangentialSpring> tangential_spring(const LawSelection& laws, const ContactParams& p) {
  std::optional<TangentialSpring> out;
  with_laws(laws, [&]<class T, class R>() {
    if constexpr (TangentialAPrioriSpring<T>) out = T::spring(p);
  });
  return out;
}

std::optional<RollingSpring> rolling_spring(const LawSelection& laws, const ContactParams& p, const ContactBodies& b,
                                            const ContactKinematics& geometry) {
  std::optional<RollingSpring> out;
  if (!p.rolling) return out;
  with_laws(laws, [&]<class T, class R>() {
    if constexpr (RollingAPrioriSpring<R>) out = R::spring(ContactInput{p, b, geometry});
  });
  return out;
}

Config parse_config(int argc, const char* const* argv) { return parse_config(law_catalog(), argc, argv); }
Config parse_config_text(const std::string& ini, const std::vector<std::string>& overrides) {
  return parse_config_text(law_catalog(), ini, overrides);
}
std::string config_help() { return config_help(law_catalog()); }
boost::program_options::options_description config_schema() { return config_schema(law_catalog()); }

}  // namespace rondel
