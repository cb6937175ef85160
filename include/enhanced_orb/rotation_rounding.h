// How the rotation of rBRIEF's test points rounds (rbrief.h), apart so that the instruction-set
// kernels can name it without the rest of the descriptor's header.
#ifndef ENHANCED_ORB_ROTATION_ROUNDING_H
#define ENHANCED_ORB_ROTATION_ROUNDING_H

namespace enhanced_orb {

// How the rotation of a test point (x, y) by an angle of cosine a and sine b rounds, in single
// precision: x a - y b and x b + y a with each product rounded (kNone), or with the first or the
// second product fused into the sum (one rounding), as a compiler contracts them where the CPU has
// fused multiply-add: Debian's arm64 OpenCV is built so, its x86-64 one is not. At an exact .5 tie
// the rounded point then moves by a pixel, and one bit of the descriptor may change.
enum class Fusion { kNone, kFirst, kSecond };
struct RotationRounding {
  Fusion x = Fusion::kNone;  // x a - y b: kFirst is fma(x, a, -(y b)), kSecond fma(-y, b, x a)
  Fusion y = Fusion::kNone;  // x b + y a: kFirst is fma(x, b, y a), kSecond fma(y, a, x b)
};
bool operator==(const RotationRounding& l, const RotationRounding& r);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ROTATION_ROUNDING_H
