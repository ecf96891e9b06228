// The step kernels of every normal law but the default one (linear), in a translation unit of their own
// (LawRows.hpp): instantiated next to the linear kernels (LawRegistry.cpp) they change GCC's inlining of the rolling
// laws into those kernels' hot loop.
#include "physics/LawRows.hpp"

namespace rondel::registry {

KernelOps select_normal_law_kernel(const LawSelection& laws) {
  KernelOps ops;
  with_kernel_laws(laws, [&]<class N, class T, class R>() {
    if constexpr (!std::is_same_v<N, NormalLaws::First> && compatible<N, T>()) {
      using K = ContactKernel<N, T, R>;
      ops = KernelOps{&K::run, select_initial_forces(laws), &K::stored_energy};
    }
  });
  return ops;
}

}  // namespace rondel::registry
