// Which vector instruction set the extraction kernels use, chosen at run time.
#ifndef ENHANCED_ORB_SIMD_H
#define ENHANCED_ORB_SIMD_H

#include <string>
#include <vector>

namespace enhanced_orb {

// kScalar is the reference every other level is tested against; kVector128 is the 16-byte level:
// SSE2 on x86-64, NEON on aarch64 (GCC's generic vectors elsewhere); kAvx2 is x86-64 with AVX2 and
// FMA. There is no AVX-512 level: its 64-byte kernels were measured slower than the AVX2 ones on an
// AVX-512 machine (docs/RESULTS.md, "Speed").
enum class SimdLevel { kScalar = 0, kVector128 = 1, kAvx2 = 2 };

// The levels this build has kernels for and this CPU can run, lowest first. A build configured
// with -DENHANCED_ORB_PORTABLE=ON has kScalar and kVector128 only.
std::vector<SimdLevel> supportedSimdLevels();

// The level in use: the best supported one, unless lowered by setSimdLevel() or by the
// environment variable ENHANCED_ORB_SIMD (a name toString() gives on this architecture: scalar,
// sse2, avx2 on x86-64; scalar, neon on aarch64) when the process started.
SimdLevel activeSimdLevel();

// Uses `level`, or the best supported level below it. Returns the level now in use. Meant for
// tests and benchmarks: it is process-wide, and results are identical at every level.
SimdLevel setSimdLevel(SimdLevel level);

// "scalar"; kVector128 is "sse2" on x86-64, "neon" on aarch64, "vector128" elsewhere; "avx2".
const char* toString(SimdLevel level);
bool parseSimdLevel(const std::string& name, SimdLevel& out);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_SIMD_H
