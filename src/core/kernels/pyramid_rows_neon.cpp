// The pyramid's row passes (pyramid_rows.h) in NEON intrinsics: the 16-byte level on aarch64, where
// fused multiply-add is part of the base instruction set (so the smoothing runs here too, not only
// at an AVX2 level as on x86). Rows too short for a vector go to the scalar kernels.
#include <arm_neon.h>

#include "kernels/pyramid_rows.h"

namespace enhanced_orb {
namespace kernels {

void linearRowVector128(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out) {
  const uint16x8_t full = vdupq_n_u16(256);
  for (int b = 0; b < taps.blocks; ++b) {
    // Each output's two source pixels as the low and high byte of a 16-bit lane.
    const uint8x16_t bytes = vld1q_u8(src + taps.block_start[b]);
    const uint16x8_t pairs = vreinterpretq_u16_u8(vqtbl1q_u8(bytes, vld1q_u8(taps.block_shuffle + 16 * b)));
    const uint16x8_t p0 = vandq_u16(pairs, vdupq_n_u16(0xFF));
    const uint16x8_t p1 = vshrq_n_u16(pairs, 8);
    const uint16x8_t w = vld1q_u16(taps.weight + 8 * b);
    // (256 - w) p0 + w p1 lies in [0, 65280]: exact in 16-bit lanes.
    vst1q_u16(out + 8 * b, vmlaq_u16(vmulq_u16(vsubq_u16(full, w), p0), w, p1));
  }
  // The outputs after the vectors, by the scalar kernel.
  const int done = 8 * taps.blocks;
  const LinearTaps tail{taps.index + done, taps.weight + done, taps.n - done, nullptr, nullptr, 0};
  linearRowScalar(src, tail, out + done);
}

void linearColumnVector128(const std::uint16_t* a, const std::uint16_t* b, int weight, int n, std::uint8_t* out) {
  if (n < 8) {
    linearColumnScalar(a, b, weight, n, out);
    return;
  }
  const uint16_t wa = static_cast<uint16_t>(256 - weight);
  const uint16_t wb = static_cast<uint16_t>(weight);
  auto block = [&](int x) {
    const uint16x8_t va = vld1q_u16(a + x);
    const uint16x8_t vb = vld1q_u16(b + x);
    const uint32x4_t lo = vmlal_n_u16(vmull_n_u16(vget_low_u16(va), wa), vget_low_u16(vb), wb);
    const uint32x4_t hi = vmlal_n_u16(vmull_n_u16(vget_high_u16(va), wa), vget_high_u16(vb), wb);
    // (sum + 2^15) >> 16, at most 255.
    const uint16x8_t words = vcombine_u16(vrshrn_n_u32(lo, 16), vrshrn_n_u32(hi, 16));
    vst1_u8(out + x, vmovn_u16(words));
  };
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    block(x);
  }
  if (x < n) {
    block(n - 8);  // overlapping: rewrites the same values
  }
}

void gaussianRowVector128(const std::uint8_t* src, int n, const float* k, float* out) {
  float32x4_t taps[7];
  for (int j = 0; j < 7; ++j) {
    taps[j] = vdupq_n_f32(k[j]);
  }
  // Four outputs read 10 pixels: one 16-byte load while it stays inside the row (n + 6 pixels),
  // widened to three float vectors; the pixels at j = 1..6 are shifts across them (vext).
  int x = 0;
  for (; x + 16 <= n + 6; x += 4) {
    const uint8x16_t bytes = vld1q_u8(src + x);
    const uint16x8_t low = vmovl_u8(vget_low_u8(bytes));
    const float32x4_t p0 = vcvtq_f32_u32(vmovl_u16(vget_low_u16(low)));
    const float32x4_t p1 = vcvtq_f32_u32(vmovl_u16(vget_high_u16(low)));
    const float32x4_t p2 = vcvtq_f32_u32(vmovl_u16(vget_low_u16(vmovl_u8(vget_high_u8(bytes)))));
    float32x4_t r = vmulq_f32(taps[0], p0);
    r = vfmaq_f32(r, taps[1], vextq_f32(p0, p1, 1));  // r + k_j s[x + j], one rounding each
    r = vfmaq_f32(r, taps[2], vextq_f32(p0, p1, 2));
    r = vfmaq_f32(r, taps[3], vextq_f32(p0, p1, 3));
    r = vfmaq_f32(r, taps[4], p1);
    r = vfmaq_f32(r, taps[5], vextq_f32(p1, p2, 1));
    r = vfmaq_f32(r, taps[6], vextq_f32(p1, p2, 2));
    vst1q_f32(out + x, r);
  }
  // The last outputs, by the scalar kernel.
  gaussianRowScalar(src + x, n - x, k, out + x);
}

void gaussianColumnVector128(const float* const* rows, int n, const float* k, std::uint8_t* out) {
  if (n < 8) {
    gaussianColumnScalar(rows, n, k, out);
    return;
  }
  const float32x4_t k0 = vdupq_n_f32(k[0]), k1 = vdupq_n_f32(k[1]), k2 = vdupq_n_f32(k[2]), k3 = vdupq_n_f32(k[3]);
  auto sums = [&](int x) {
    float32x4_t c = vmulq_f32(k3, vld1q_f32(rows[3] + x));
    c = vfmaq_f32(c, k2, vaddq_f32(vld1q_f32(rows[2] + x), vld1q_f32(rows[4] + x)));
    c = vfmaq_f32(c, k1, vaddq_f32(vld1q_f32(rows[1] + x), vld1q_f32(rows[5] + x)));
    c = vfmaq_f32(c, k0, vaddq_f32(vld1q_f32(rows[0] + x), vld1q_f32(rows[6] + x)));
    return vcvtnq_s32_f32(c);  // nearest, ties to even
  };
  auto block = [&](int x) {
    const int16x8_t words = vcombine_s16(vqmovn_s32(sums(x)), vqmovn_s32(sums(x + 4)));
    vst1_u8(out + x, vqmovun_s16(words));  // saturated to [0, 255]
  };
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    block(x);
  }
  if (x < n) {
    block(n - 8);
  }
}

}  // namespace kernels
}  // namespace enhanced_orb
