#pragma once
// What a contact law must provide, one concept per kind. The registry (LawRows.hpp) checks every row
// against its concept with a static_assert, so a law type that lacks a member fails to compile there,
// with the law's name in the instantiation and the missing requirement in the note.
//
// Every law: `name` (its keyword for contact.<kind>), `block` (its INI parameter block, core/LawSpec.hpp,
// or nullptr when it has no parameters). Tangential and rolling laws: `slots` (history columns, in the
// order the law indexes them) and either `spring(...)` (its a-priori spring for the critical step,
// docs/physics.md section 4) or `no_spring` (why there is none: no spring, or one that grows with F_n).
#include <concepts>
#include <cstddef>

#include "core/ContactParams.hpp"
#include "core/LawSpec.hpp"
#include "physics/ContactKinematics.hpp"
#include "physics/LawTypes.hpp"

namespace rondel {

template <class L>
concept DeclaredLaw = requires {
  { L::name } -> std::convertible_to<const char*>;
  { L::block } -> std::convertible_to<const LawBlock*>;
};

// The history slots: their names (`slots`) and the law's History, a struct of references to them, one member per
// name, made from the columns with history_row (LawTypes.hpp).
template <class L>
concept HistoryLaw = requires(double* const* columns) {
  { L::slots.size() } -> std::convertible_to<std::size_t>;
  { L::slots.data() } -> std::convertible_to<const char* const*>;
  { history_row<typename L::History, L::slots.size()>(columns, std::size_t{}) } -> std::same_as<typename L::History>;
};

// "This law has no a-priori spring for the critical step", with the reason.
template <class L>
concept DeclaresNoSpring = requires {
  { L::no_spring } -> std::convertible_to<const char*>;
};

template <class L>
concept NormalLawType = DeclaredLaw<L> && HistoryLaw<L> && requires(const ContactInput& in, typename L::History h) {
  { L::force(in, h) } -> std::same_as<NormalForce>;
  { L::stored(in, h) } -> std::same_as<double>;
  { L::linearised(in) } -> std::same_as<ContactParams>;
  { L::kStiffening } -> std::convertible_to<bool>;
};

// A normal law whose unloading is stiffer than what the other laws see of it (walton_braun: K2 = K1/e^2 against
// K1) declares `stiffest(in)`, the parameters with that stiffness: the normal mode of the critical step and the
// servo's gain take it. Every other law's stiffest spring is its linearised one.
template <class L>
ContactParams stiffest_normal(const ContactInput& in) {
  if constexpr (requires { L::stiffest(in); })
    return L::stiffest(in);
  else
    return L::linearised(in);
}

// A normal law that dissipates by hysteresis declares `kHysteresis = true` (walton_braun): the kernel books its
// NormalForce::hysteresis (D_n_hyst), the others' kernels have no such term.
template <class L>
constexpr bool hysteretic() {
  if constexpr (requires { L::kHysteresis; })
    return L::kHysteresis;
  else
    return false;
}

template <class L>
concept TangentialAPrioriSpring = requires(const ContactParams& p) {
  { L::spring(p) } -> std::same_as<TangentialSpring>;
};

template <class L>
concept TangentialCalls = requires(const ContactInput& in, typename L::History h) {
  { L::kFriction } -> std::convertible_to<bool>;
  { L::force(in, h) } -> std::same_as<TangentialForce>;
  { L::stored(in, h) } -> std::same_as<double>;
};

template <class L>
concept TangentialLawType = DeclaredLaw<L> && HistoryLaw<L> && TangentialCalls<L> &&
    (TangentialAPrioriSpring<L> || DeclaresNoSpring<L>);

template <class L>
concept RollingAPrioriSpring = requires(const ContactInput& in) {
  { L::spring(in) } -> std::same_as<RollingSpring>;
};

template <class L>
concept RollingCalls = requires(const ContactInput& in, typename L::History h) {
  { L::kActive } -> std::convertible_to<bool>;
  { L::moment(in, h) } -> std::same_as<RollingCouple>;
  { L::stored(in, h) } -> std::same_as<double>;
  { L::cap(in) } -> std::same_as<double>;
};

template <class L>
concept RollingLawType = DeclaredLaw<L> && HistoryLaw<L> && RollingCalls<L> &&
    (RollingAPrioriSpring<L> || DeclaresNoSpring<L>);

// A tangential law whose stiffness depends on the contact (mindlin) gives the coulomb spring-dashpot it is at the
// kinematics of `in` (the critical step at the largest overlap); the others are that spring-dashpot already.
template <class L>
ContactParams linearised_tangential(const ContactInput& in) {
  if constexpr (requires { L::linearised(in); })
    return L::linearised(in);
  else
    return in.p;
}

// A rolling law with kernel variants for some parameter tables declares them (wang): `lean(p)`, true for a pair
// or wall whose parameters let the lean variant stand for the law (no dashpot), and `Variant<lean, every_row>`, the
// law for a table whose every pair and wall is lean, and where moreover every one has rolling resistance.
template <class L>
concept HasKernelVariants = requires(const ContactParams& p) {
  { L::lean(p) } -> std::convertible_to<bool>;
  typename L::template Variant<true, true>;
};

// A rolling law whose couple on disc 2 is not -M1 declares `kOwnCouples = true` (force_proportional: each
// disc's couple comes from its own spin); its rows keep both couples. Every other law's rows keep M1 only.
template <class L>
constexpr bool own_couples() {
  if constexpr (requires { L::kOwnCouples; })
    return L::kOwnCouples;
  else
    return false;
}

// A rolling law that releases stored energy when a contact breaks declares `kBreaks = true` (jiang_brittle);
// the kernel books E_r_break for it only.
template <class L>
constexpr bool breaks() {
  if constexpr (requires { L::kBreaks; })
    return L::kBreaks;
  else
    return false;
}

// A kernel variant of a rolling law for parameter tables in which every pair and every wall has rolling
// resistance (ContactParams::rolling, the default) declares `kEveryRow = true`: the kernel then applies it
// without testing p.rolling on each contact (LawSelection::rolling_every_row).
template <class L>
constexpr bool rolls_every_row() {
  if constexpr (requires { L::kEveryRow; })
    return L::kEveryRow;
  else
    return false;
}

// A rolling law whose dissipation is zero on most contacts (no dashpot, plastic work only where the cap is
// reached) declares `kSparseLoss = true`: the kernel then books RollingCouple::plastic and ::dashpot only where
// one is not zero. The sums start at +0 and every term is >= 0, so skipping a +0 term leaves their bits as
// they were.
template <class L>
constexpr bool sparse_loss() {
  if constexpr (requires { L::kSparseLoss; })
    return L::kSparseLoss;
  else
    return false;
}

// A law that needs every material's elastic constants (E, nu) declares `kElastic = true` (hertz, mindlin); a law
// that works with one normal law only declares `kNeedsNormal` (its keyword) and `kNeedsWhy` (mindlin: hertz). The
// configuration checks both through the catalog (LawInfo), so no other file names those laws.
template <class L>
constexpr bool elastic_law() {
  if constexpr (requires { L::kElastic; })
    return L::kElastic;
  else
    return false;
}
template <class L>
constexpr bool stiffening_law() {
  if constexpr (requires { L::kStiffening; })
    return L::kStiffening;
  else
    return false;
}
template <class L>
constexpr const char* needed_normal() {
  if constexpr (requires { L::kNeedsNormal; })
    return L::kNeedsNormal;
  else
    return nullptr;
}
template <class L>
constexpr const char* needed_why() {
  if constexpr (requires { L::kNeedsWhy; })
    return L::kNeedsWhy;
  else
    return "";
}

// A rolling law that is not objective (its couple changes under a rigid spin superposed on the pair) declares why,
// `not_objective` (force_proportional: each disc's own spin; constant_torque: its limiter reads the spins); the
// conformance tests check every other law's invariance under a superposed spin.
template <class L>
constexpr bool objective() {
  return !requires { L::not_objective; };
}
// A rolling law whose couple's work the ledger does not split into stored energy and dissipation declares why,
// `unsplit_work` (docs/physics.md section 5: it is left in D_other); the conformance tests check every other
// law's split against the energy of a contact.
template <class L>
constexpr bool splits_work() {
  return !requires { L::unsplit_work; };
}

// The rolling couple columns of a law's rows (ContactTable::couples()): 0, 1 or 2.
template <class L>
constexpr int couple_columns() {
  return !L::kActive ? 0 : (own_couples<L>() ? 2 : 1);
}

}  // namespace rondel
