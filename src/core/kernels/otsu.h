// The Otsu thresholds of many cell histograms at once (adaptive_threshold.h, otsuThresholds).
#ifndef ENHANCED_ORB_KERNELS_OTSU_H
#define ENHANCED_ORB_KERNELS_OTSU_H

#include <cstdint>

namespace enhanced_orb {
namespace kernels {

// thresholds[c] for the `count` histograms of 256 counts each at histograms + 256 c.
using OtsuKernel = void (*)(const std::uint32_t* histograms, int count, int* thresholds);

// Four cells at a time in the lanes of AVX2 vectors, each lane's arithmetic step for step that of
// the scalar reference (adaptive_threshold.cpp), so that both give the same thresholds; the levels
// before a cell's first count and from its last on change nothing and are left out.
void otsuThresholdsAvx2(const std::uint32_t* histograms, int count, int* thresholds);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_OTSU_H
