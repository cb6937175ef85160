// The Otsu thresholds of many cells (otsu.h) on AVX2, four cells to a vector of doubles. Nothing
// here may instantiate an inline function or template shared with other files: the linker keeps
// one copy of such a function for the whole library, possibly this file's, built for an instruction
// set the CPU may not have.
#include <cfloat>

#include <immintrin.h>

#include "kernels/otsu.h"

namespace enhanced_orb {
namespace kernels {
namespace {

constexpr int kGroups = 8;  // cells worked on side by side: 32, enough for their divisions to overlap

// Four cells' state: the scalar reference's, lane by lane.
struct Group {
  const std::uint32_t* rows[4];  // each cell's histogram (a row of zeros past the last cell)
  int first, last;               // the levels where some lane's state may change
  __m256d scale, mu, q1, mu1, max_sigma, best;
};

// At most 4 kGroups cells.
void otsuBlock(const std::uint32_t* histograms, int count, int* thresholds) {
  static const std::uint32_t kZeros[256] = {};
  Group groups[kGroups];
  const int n_groups = (count + 3) / 4;
  for (int g = 0; g < n_groups; ++g) {
    Group& group = groups[g];
    double scale[4], mu[4];
    group.first = 256;
    group.last = -1;
    for (int lane = 0; lane < 4; ++lane) {
      const int c = 4 * g + lane;
      const std::uint32_t* h = c < count ? histograms + 256 * c : kZeros;
      group.rows[lane] = h;
      // The sums in whole numbers: exact, as the reference's in doubles are (below 2^53).
      unsigned long long n = 0, sum = 0;
      for (int i = 0; i < 256; ++i) {
        n += h[i];
        sum += static_cast<unsigned long long>(i) * h[i];
        if (h[i] != 0) {
          group.first = i < group.first ? i : group.first;
          group.last = i > group.last ? i : group.last;
        }
      }
      scale[lane] = n == 0 ? 0.0 : 1.0 / static_cast<double>(n);
      mu[lane] = static_cast<double>(sum) * scale[lane];
    }
    group.scale = _mm256_loadu_pd(scale);
    group.mu = _mm256_loadu_pd(mu);
    group.q1 = group.mu1 = group.max_sigma = group.best = _mm256_setzero_pd();
  }
  // Before a lane's first count its q1 stays 0, and from its last count on q2 is below FLT_EPSILON:
  // every lane skips those levels in the reference, and nothing it skips is read again.
  int first = 256, last = -1;
  for (int g = 0; g < n_groups; ++g) {
    first = groups[g].first < first ? groups[g].first : first;
    last = groups[g].last > last ? groups[g].last : last;
  }
  const __m256d one = _mm256_set1_pd(1.0);
  const __m256d low = _mm256_set1_pd(FLT_EPSILON);
  const __m256d high = _mm256_set1_pd(1.0 - FLT_EPSILON);
  for (int i = first; i <= last; ++i) {
    const __m256d level = _mm256_set1_pd(i);
    for (int g = 0; g < n_groups; ++g) {
      Group& s = groups[g];
      if (i < s.first || i > s.last) {
        continue;
      }
      const __m128i counts = _mm_set_epi32(static_cast<int>(s.rows[3][i]), static_cast<int>(s.rows[2][i]),
                                           static_cast<int>(s.rows[1][i]), static_cast<int>(s.rows[0][i]));
      const __m256d p = _mm256_mul_pd(_mm256_cvtepi32_pd(counts), s.scale);
      const __m256d mu1 = _mm256_mul_pd(s.mu1, s.q1);
      s.q1 = _mm256_add_pd(s.q1, p);
      const __m256d q2 = _mm256_sub_pd(one, s.q1);
      const __m256d skip = _mm256_or_pd(_mm256_cmp_pd(_mm256_min_pd(s.q1, q2), low, _CMP_LT_OQ),
                                        _mm256_cmp_pd(_mm256_max_pd(s.q1, q2), high, _CMP_GT_OQ));
      const __m256d mu1_next = _mm256_div_pd(_mm256_add_pd(mu1, _mm256_mul_pd(level, p)), s.q1);
      const __m256d mu2 = _mm256_div_pd(_mm256_sub_pd(s.mu, _mm256_mul_pd(s.q1, mu1_next)), q2);
      const __m256d d = _mm256_sub_pd(mu1_next, mu2);
      const __m256d sigma = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(s.q1, q2), d), d);
      s.mu1 = _mm256_blendv_pd(mu1_next, mu1, skip);
      const __m256d better = _mm256_andnot_pd(skip, _mm256_cmp_pd(sigma, s.max_sigma, _CMP_GT_OQ));
      s.max_sigma = _mm256_blendv_pd(s.max_sigma, sigma, better);
      s.best = _mm256_blendv_pd(s.best, level, better);
    }
  }
  for (int g = 0; g < n_groups; ++g) {
    double best[4], scale[4];
    _mm256_storeu_pd(best, groups[g].best);
    _mm256_storeu_pd(scale, groups[g].scale);
    for (int lane = 0; lane < 4 && 4 * g + lane < count; ++lane) {
      thresholds[4 * g + lane] = scale[lane] == 0.0 ? 0 : static_cast<int>(best[lane]);
    }
  }
}

}  // namespace

void otsuThresholdsAvx2(const std::uint32_t* histograms, int count, int* thresholds) {
  for (int c = 0; c < count; c += 4 * kGroups) {
    otsuBlock(histograms + 256 * c, count - c < 4 * kGroups ? count - c : 4 * kGroups, thresholds + c);
  }
}

}  // namespace kernels
}  // namespace enhanced_orb
