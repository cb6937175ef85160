#include "enhanced_orb/simd.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>

namespace enhanced_orb {
namespace {

bool cpuRuns(SimdLevel level) {
  switch (level) {
    case SimdLevel::kScalar:
    case SimdLevel::kVector128:
      return true;
#if defined(ENHANCED_ORB_X86_KERNELS)
    case SimdLevel::kAvx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
    case SimdLevel::kAvx2:
      return false;
#endif
  }
  return false;
}

SimdLevel initialLevel() {
  const std::vector<SimdLevel> levels = supportedSimdLevels();
  SimdLevel best = levels.back();
  SimdLevel wanted = best;
  if (const char* name = std::getenv("ENHANCED_ORB_SIMD"); name && parseSimdLevel(name, wanted)) {
    best = std::min(best, wanted);
  }
  return best;
}

std::atomic<SimdLevel>& current() {
  static std::atomic<SimdLevel> level{initialLevel()};
  return level;
}

}  // namespace

std::vector<SimdLevel> supportedSimdLevels() {
  std::vector<SimdLevel> levels;
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kVector128, SimdLevel::kAvx2}) {
    if (cpuRuns(level)) {
      levels.push_back(level);
    }
  }
  return levels;
}

SimdLevel activeSimdLevel() {
  return current().load(std::memory_order_relaxed);
}

SimdLevel setSimdLevel(SimdLevel level) {
  SimdLevel chosen = SimdLevel::kScalar;
  for (SimdLevel supported : supportedSimdLevels()) {
    if (supported <= level) {
      chosen = supported;
    }
  }
  current().store(chosen, std::memory_order_relaxed);
  return chosen;
}

const char* toString(SimdLevel level) {
  switch (level) {
    case SimdLevel::kScalar:
      return "scalar";
    case SimdLevel::kVector128:
#if defined(__x86_64__) || defined(__i386__)
      return "sse2";
#elif defined(__aarch64__)
      return "neon";
#else
      return "vector128";
#endif
    case SimdLevel::kAvx2:
      return "avx2";
  }
  return "?";
}

bool parseSimdLevel(const std::string& name, SimdLevel& out) {
  for (SimdLevel level : {SimdLevel::kScalar, SimdLevel::kVector128, SimdLevel::kAvx2}) {
    if (name == toString(level)) {
      out = level;
      return true;
    }
  }
  return false;
}

}  // namespace enhanced_orb
