// The step kernels of the normal laws whose stiffness grows with overlap (kStiffening), in a translation unit of
// their own (LawRows.hpp): instantiated next to the other normal laws' kernels (LawRegistry.cpp) they change
// GCC's inlining of the rolling laws into those kernels' hot loop.
#include "physics/LawRows.hpp"

namespace rondel::registry {

KernelOps select_stiffening_kernel(const LawSelection& laws) {
  KernelOps ops;
  with_kernel_laws(laws, [&]<class N, class T, class R>() {
    if constexpr (N::kStiffening && compatible<N, T>()) {
      using K = ContactKernel<N, T, R>;
      ops = KernelOps{&K::run, select_initial_forces(laws), &K::stored_energy};
    }
  });
  return ops;
}

}  // namespace rondel::registry
