// Every (normal, tangential, rolling) combination is instantiated here, once.
#include "physics/LawRegistry.hpp"

#include <tuple>

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

// One row per rolling law: its enum value and its type (the name comes from the type).
using RollingLaws = std::tuple<RollingNone, RollingJiangPlastic, RollingJiangBrittle, RollingWang, RollingIwashitaOda,
                               RollingForceProportional, RollingConstantTorque, RollingDisplacementDamping>;
constexpr RollingLaw kRollingOrder[] = {RollingLaw::none,           RollingLaw::jiang_plastic,
                                        RollingLaw::jiang_brittle,  RollingLaw::wang,
                                        RollingLaw::iwashita_oda,   RollingLaw::force_proportional,
                                        RollingLaw::constant_torque, RollingLaw::displacement_damping};

// Calls f.template operator()<Law>() for the rolling law type selected by `law`.
template <class F, std::size_t I = 0>
auto with_rolling_type(RollingLaw law, F&& f) {
  if constexpr (I + 1 < std::tuple_size_v<RollingLaws>) {
    if (kRollingOrder[I] != law) return with_rolling_type<F, I + 1>(law, std::forward<F>(f));
  }
  return f.template operator()<std::tuple_element_t<I, RollingLaws>>();
}

template <class Law>
void append_slots(std::vector<std::string>& out) {
  for (const char* s : Law::slots) out.emplace_back(s);
}

template <class N, class T>
KernelOps ops_for(RollingLaw law) {
  return with_rolling_type(law, []<class R>() {
    return KernelOps{&ContactKernel<N, T, R>::run, &ContactKernel<N, T, R>::stored_energy};
  });
}

}  // namespace

std::string to_string(NormalLaw) { return "linear"; }
std::string to_string(TangentialLaw law) { return law == TangentialLaw::coulomb ? "coulomb" : "none"; }
std::string to_string(RollingLaw law) {
  return with_rolling_type(law, []<class R>() { return std::string(R::name); });
}

bool parse_rolling_law(const std::string& name, RollingLaw& out) {
  for (RollingLaw law : kRollingOrder)
    if (to_string(law) == name) {
      out = law;
      return true;
    }
  return false;
}

std::string rolling_law_names() {
  std::string s;
  for (RollingLaw law : kRollingOrder) s += (s.empty() ? "" : " | ") + to_string(law);
  return s;
}

KernelOps select_kernel(const LawSelection& laws) {
  if (laws.tangential == TangentialLaw::coulomb) return ops_for<NormalLinear, TangentialCoulomb>(laws.rolling);
  return ops_for<NormalLinear, TangentialNone>(laws.rolling);
}

std::vector<std::string> history_slots(const LawSelection& laws) {
  std::vector<std::string> out;
  if (laws.tangential == TangentialLaw::coulomb) append_slots<TangentialCoulomb>(out);
  with_rolling_type(laws.rolling, [&out]<class R>() {
    append_slots<R>(out);
    return 0;
  });
  return out;
}

ContactTable make_contact_table(const LawSelection& laws) {
  return ContactTable(history_slots(laws), laws.rolling != RollingLaw::none);
}

}  // namespace rondel
