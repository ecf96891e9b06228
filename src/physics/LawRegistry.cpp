// The registry: ONE list of law types per kind. Adding a law is one file (its type) plus one row here;
// each row is checked against its kind's concept (LawConcepts.hpp), so a law that lacks a member fails to
// compile with the law named in the failed static_assert's instantiation. Every (normal, tangential,
// rolling) combination is instantiated here, once.
#include "physics/LawRegistry.hpp"

#include "core/ConfigSchema.hpp"
#include "core/Errors.hpp"
#include "physics/LawConcepts.hpp"
#include "physics/NormalLinear.hpp"
#include "physics/RollingConstantTorque.hpp"
#include "physics/RollingDisplacementDamping.hpp"
#include "physics/RollingForceProportional.hpp"
#include "physics/RollingIwashitaOda.hpp"
#include "physics/RollingJiangBrittle.hpp"
#include "physics/RollingJiangPlastic.hpp"
#include "physics/RollingNone.hpp"
#include "physics/RollingWang.hpp"
#include "physics/TangentialLaws.hpp"

namespace rondel {

namespace {

// A row check per kind: instantiated once per law, so a failure names the law (Row<Law>).
template <class L>
struct NormalRow {
  static_assert(NormalLawType<L>, "this normal law lacks a member that NormalLawType requires (LawConcepts.hpp)");
  static constexpr bool ok = true;
};
template <class L>
struct TangentialRow {
  static_assert(TangentialLawType<L>,
                "this tangential law lacks a member that TangentialLawType requires (LawConcepts.hpp)");
  static constexpr bool ok = true;
};
template <class L>
struct RollingRow {
  static_assert(RollingLawType<L>, "this rolling law lacks a member that RollingLawType requires (LawConcepts.hpp)");
  static constexpr bool ok = true;
};

// A list of law types of one kind, every row checked by Row<Law>.
template <template <class> class Row, class... Laws>
struct LawList {
  static_assert((Row<Laws>::ok && ...));
  // Calls f.template operator()<Law>() for the law named `keyword`; false when no law has that name.
  template <class F>
  static bool with(const std::string& keyword, F&& f) {
    return ((keyword == Laws::name ? (f.template operator()<Laws>(), true) : false) || ...);
  }
  static LawKind kind(const char* name) { return {name, {LawInfo{Laws::name, Laws::block}...}}; }
};

// The registry rows. The first law of each list is the default of its contact.<kind> key.
using NormalLaws = LawList<NormalRow, NormalLinear>;
using TangentialLaws = LawList<TangentialRow, TangentialCoulomb, TangentialNone>;
using RollingLaws =
    LawList<RollingRow, RollingNone, RollingJiangPlastic, RollingJiangBrittle, RollingWang, RollingIwashitaOda,
            RollingForceProportional, RollingConstantTorque, RollingDisplacementDamping>;

[[noreturn]] void unknown(const LawKind& kind, const std::string& keyword) {
  throw ConfigError("contact." + std::string(kind.kind) + " = " + keyword + " is not one of " + kind.keywords());
}

// Calls f.template operator()<T, R>() for the selected tangential and rolling laws.
template <class F>
void with_laws(const LawSelection& laws, F&& f) {
  const LawCatalog& catalog = law_catalog();
  if (!catalog.tangential.find(laws.tangential)) unknown(catalog.tangential, laws.tangential);
  if (!catalog.rolling.find(laws.rolling)) unknown(catalog.rolling, laws.rolling);
  TangentialLaws::with(laws.tangential, [&]<class T>() {
    RollingLaws::with(laws.rolling, [&]<class R>() { f.template operator()<T, R>(); });
  });
}

}  // namespace

const LawCatalog& law_catalog() {
  static const LawCatalog catalog{NormalLaws::kind("normal"), TangentialLaws::kind("tangential"),
                                  RollingLaws::kind("rolling")};
  return catalog;
}

KernelOps select_kernel(const LawSelection& laws) {
  KernelOps ops;
  if (!law_catalog().normal.find(laws.normal)) unknown(law_catalog().normal, laws.normal);
  NormalLaws::with(laws.normal, [&]<class N>() {
    with_laws(laws, [&]<class T, class R>() {
      using K = ContactKernel<N, T, R>;
      ops = KernelOps{&K::run, &K::initial_forces, &K::stored_energy};
    });
  });
  return ops;
}

std::vector<std::string> history_slots(const LawSelection& laws) {
  std::vector<std::string> out;
  with_laws(laws, [&out]<class T, class R>() {
    for (const char* s : T::slots) out.emplace_back(s);
    for (const char* s : R::slots) out.emplace_back(s);
  });
  return out;
}

ContactTable make_contact_table(const LawSelection& laws) {
  bool rolling = false;
  with_laws(laws, [&rolling]<class T, class R>() { rolling = R::kActive; });
  return ContactTable(history_slots(laws), rolling);
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
    if constexpr (RollingAPrioriSpring<R>) out = R::spring(p, b, geometry);
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
