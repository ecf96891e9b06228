// Every (normal, tangential, rolling) combination is instantiated here, once.
#include "physics/LawRegistry.hpp"

#include "physics/NormalLinear.hpp"
#include "physics/RollingNone.hpp"
#include "physics/TangentialLaws.hpp"

namespace rondel {

std::string to_string(NormalLaw) { return "linear"; }
std::string to_string(TangentialLaw law) { return law == TangentialLaw::coulomb ? "coulomb" : "none"; }
std::string to_string(RollingLaw) { return "none"; }

namespace {

template <class N, class T, class R>
constexpr KernelFn kernel() {
  return &ContactKernel<N, T, R>::run;
}

template <class N, class T>
KernelFn with_rolling(RollingLaw law) {
  switch (law) {
    case RollingLaw::none:
      return kernel<N, T, RollingNone>();
  }
  return nullptr;
}

template <class N>
KernelFn with_tangential(const LawSelection& laws) {
  switch (laws.tangential) {
    case TangentialLaw::none:
      return with_rolling<N, TangentialNone>(laws.rolling);
    case TangentialLaw::coulomb:
      return with_rolling<N, TangentialCoulomb>(laws.rolling);
  }
  return nullptr;
}

template <class Law>
void append_slots(std::vector<std::string>& out) {
  for (const char* s : Law::slots) out.emplace_back(s);
}

}  // namespace

KernelFn select_kernel(const LawSelection& laws) { return with_tangential<NormalLinear>(laws); }

std::vector<std::string> history_slots(const LawSelection& laws) {
  std::vector<std::string> out;
  if (laws.tangential == TangentialLaw::coulomb) append_slots<TangentialCoulomb>(out);
  switch (laws.rolling) {
    case RollingLaw::none:
      append_slots<RollingNone>(out);
      break;
  }
  return out;
}

ContactTable make_contact_table(const LawSelection& laws) {
  return ContactTable(history_slots(laws), laws.rolling != RollingLaw::none);
}

}  // namespace rondel
