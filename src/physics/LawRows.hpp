#pragma once
// The registry rows: ONE list of law types per kind. Adding a law is one file (its type) plus one row
// here; each row is checked against its kind's concept (LawConcepts.hpp), so a law that lacks a member
// fails to compile with the law named in the failed static_assert's instantiation (Row<Law>).
// Internal to the registry's translation units (LawRegistry.cpp, InitialForces.cpp).
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>

#include "core/Errors.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKernel.hpp"
#include "physics/LawConcepts.hpp"
#include "physics/LawRegistry.hpp"
#include "physics/NormalHertz.hpp"
#include "physics/NormalLinear.hpp"
#include "physics/NormalWaltonBraun.hpp"
#include "physics/RollingAlonsoMarroquin.hpp"
#include "physics/RollingConstantTorque.hpp"
#include "physics/RollingDisplacementDamping.hpp"
#include "physics/RollingForceProportional.hpp"
#include "physics/RollingIwashitaOda.hpp"
#include "physics/RollingJiangBrittle.hpp"
#include "physics/RollingJiangPlastic.hpp"
#include "physics/RollingNone.hpp"
#include "physics/RollingWang.hpp"
#include "physics/TangentialLaws.hpp"
#include "physics/TangentialMindlin.hpp"

namespace rondel::registry {

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
  // The first law: the default of its contact.<kind> key.
  using First = std::tuple_element_t<0, std::tuple<Laws...>>;
  // Calls f.template operator()<Law>() for the law named `keyword`; false when no law has that name.
  template <class F>
  static bool with(const std::string& keyword, F&& f) {
    return ((keyword == Laws::name ? (f.template operator()<Laws>(), true) : false) || ...);
  }
  // The laws as the arguments of a template (the conformance tests: ::testing::Types).
  template <template <class...> class To>
  using types = To<Laws...>;
  static LawKind kind(const char* name) {
    return {name,
            {LawInfo{Laws::name, Laws::block, elastic_law<Laws>(), stiffening_law<Laws>(), needed_normal<Laws>(),
                     needed_why<Laws>()}...}};
  }
};

// The registry rows. The first law of each list is the default of its contact.<kind> key.
using NormalLaws = LawList<NormalRow, NormalLinear, NormalHertz, NormalWaltonBraun>;
using TangentialLaws = LawList<TangentialRow, TangentialCoulomb, TangentialNone, TangentialMindlin>;
using RollingLaws =
    LawList<RollingRow, RollingNone, RollingJiangPlastic, RollingJiangBrittle, RollingWang, RollingAlonsoMarroquin,
            RollingIwashitaOda, RollingForceProportional, RollingConstantTorque, RollingDisplacementDamping>;

[[noreturn]] inline void unknown(const LawKind& kind, const std::string& keyword) {
  throw ConfigError("contact." + std::string(kind.kind) + " = " + keyword + " is not one of " + kind.keywords());
}

// Calls f.template operator()<T, R>() for the selected tangential and rolling laws; throws ConfigError
// naming the key for an unknown keyword.
template <class F>
void with_laws(const LawSelection& laws, F&& f) {
  const LawCatalog& catalog = law_catalog();
  if (!catalog.tangential.find(laws.tangential)) unknown(catalog.tangential, laws.tangential);
  if (!catalog.rolling.find(laws.rolling)) unknown(catalog.rolling, laws.rolling);
  TangentialLaws::with(laws.tangential, [&]<class T>() {
    RollingLaws::with(laws.rolling, [&]<class R>() { f.template operator()<T, R>(); });
  });
}

// The law the kernel runs for the selected rolling law R: R's own Variant for the table when R declares variants
// (HasKernelVariants: wang), else R.
template <class R, class F>
void with_kernel_variant(const LawSelection& laws, F&& f) {
  if constexpr (HasKernelVariants<R>) {
    if (laws.rolling_lean && laws.rolling_every_row)
      return f.template operator()<typename R::template Variant<true, true>>();
    if (laws.rolling_lean) return f.template operator()<typename R::template Variant<true, false>>();
  }
  f.template operator()<R>();
}

// As with_laws, with the normal law first: f.template operator()<N, T, R>(), R the kernel's variant of the
// rolling law (with_kernel_variant).
template <class F>
void with_kernel_laws(const LawSelection& laws, F&& f) {
  if (!law_catalog().normal.find(laws.normal)) unknown(law_catalog().normal, laws.normal);
  NormalLaws::with(laws.normal, [&]<class N>() {
    with_laws(laws, [&]<class T, class R>() {
      with_kernel_variant<R>(laws, [&]<class V>() { f.template operator()<N, T, V>(); });
    });
  });
}

// Whether tangential law T works with normal law N (T::kNeedsNormal names N, or T needs no particular one).
template <class N, class T>
constexpr bool compatible() {
  if constexpr (needed_normal<T>() == nullptr)
    return true;
  else
    return std::string_view(needed_normal<T>()) == N::name;
}

// KernelOps::initial of the selected laws, instantiated in its own translation unit (InitialForces.cpp)
// so that it does not change how GCC inlines the laws into the step kernel (LawRegistry.cpp).
using InitialForces = void (*)(const KernelContext&, ContactTable&, ContactTable&, ForceSums);
InitialForces select_initial_forces(const LawSelection& laws);

// The step kernels of every normal law but the default (NormalLaws::First, linear), instantiated in their own
// translation unit (NormalLawKernels.cpp): next to the linear kernels they change how GCC inlines the rolling laws
// into the linear step kernel (wang: +15 % instructions per disc-step).
KernelOps select_normal_law_kernel(const LawSelection& laws);

}  // namespace rondel::registry
