// The step kernels of contact.normal = hertz, in a translation unit of their own (LawRows.hpp): instantiated
// next to the linear normal law's kernels (LawRegistry.cpp) they change GCC's inlining of the rolling laws
// into the linear kernels' hot loop.
#include <type_traits>

#include "physics/LawRows.hpp"

namespace rondel::registry {

KernelOps select_hertz_kernel(const LawSelection& laws) {
  KernelOps ops;
  with_kernel_laws(laws, [&]<class N, class T, class R>() {
    if constexpr (std::is_same_v<N, NormalHertz>) {
      using K = ContactKernel<N, T, R>;
      ops = KernelOps{&K::run, select_initial_forces(laws), &K::stored_energy};
    }
  });
  return ops;
}

}  // namespace rondel::registry
