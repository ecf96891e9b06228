// KernelOps::initial for every law combination, in a translation unit of its own: instantiating the
// non-committing kernel next to the step kernel (LawRegistry.cpp) changes GCC's inlining of the laws
// into the step kernel's hot loop.
#include "physics/LawRows.hpp"

namespace rondel::registry {

InitialForces select_initial_forces(const LawSelection& laws) {
  InitialForces initial = nullptr;
  with_kernel_laws(laws, [&]<class N, class T, class R>() {
    if constexpr (compatible<N, T>()) initial = &ContactKernel<N, T, R>::initial_forces;
  });
  return initial;
}

}  // namespace rondel::registry
