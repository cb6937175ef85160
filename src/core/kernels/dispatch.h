// Picks a kernel by instruction set: the widest one this build has at or below the level asked for.
#ifndef ENHANCED_ORB_KERNELS_DISPATCH_H
#define ENHANCED_ORB_KERNELS_DISPATCH_H

#include "enhanced_orb/simd.h"

// An x86-only kernel, or none in a build without them.
#if defined(ENHANCED_ORB_X86_KERNELS)
#define ENHANCED_ORB_X86_KERNEL(kernel) kernel
#else
#define ENHANCED_ORB_X86_KERNEL(kernel) nullptr
#endif
// An aarch64-only kernel (NEON), or none elsewhere.
#if defined(ENHANCED_ORB_NEON_KERNELS)
#define ENHANCED_ORB_NEON_KERNEL(kernel) kernel
#else
#define ENHANCED_ORB_NEON_KERNEL(kernel) nullptr
#endif

namespace enhanced_orb {
namespace kernels {

template <typename T>
struct NonDeduced {
  using type = T;
};

// The kernels of each level, scalar first; a missing one (nullptr) falls back to the next below.
template <typename Kernel>
Kernel selectKernel(SimdLevel level, Kernel scalar, typename NonDeduced<Kernel>::type vector128,
                    typename NonDeduced<Kernel>::type avx2) {
  const Kernel by_level[] = {scalar, vector128, avx2};
  for (int l = static_cast<int>(level); l > 0; --l) {
    if (by_level[l]) {
      return by_level[l];
    }
  }
  return scalar;
}

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_DISPATCH_H
