#pragma once
// Four floats as one SIMD value (GCC/Clang vector extension: SSE on x86-64, NEON on ARM), and
// the few operations the bake's hot loops need on it.
#include <cstdint>
#include <cstring>

namespace cloudlut {

typedef float Float4 __attribute__((vector_size(16)));
typedef std::int32_t Int4 __attribute__((vector_size(16)));

inline Float4 loadFloat4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline float sumFloat4(Float4 v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// e^x per lane (dimensionless), x ≤ 88: x = n ln 2 + r with |r| ≤ ln 2 / 2 (ln 2 split in two
// parts so n ln 2 is exact), e^r by its degree-7 minimax polynomial, 2^n from the exponent
// bits; 0 below x = −87.3 (where float e^x leaves the normal range). Within 2 ulp of expf.
Float4 expFloat4(Float4 x);

// ln x per lane for x > 0 (normal floats): x = m 2^e with m ∈ [√½, √2), ln m = z − z²/2 +
// z³ P(z) (z = m − 1, P a degree-8 minimax polynomial), plus e ln 2 in two parts. Within 2 ulp
// of logf.
Float4 logFloat4(Float4 x);

// atan2(y, x) per lane (radians, in [−π, π]; 0 at the origin): with a = min(|x|, |y|) /
// max(|x|, |y|) ∈ [0, 1], atan a = a·P(a²), P of degree 8 fitted here for least maximum
// relative error (1.5e-8 in exact arithmetic, 2e-7 evaluated in float); then the octant,
// π/2 − atan a where |y| > |x| and π − (…) where x < 0, and the sign of y.
Float4 atan2Float4(Float4 y, Float4 x);

}  // namespace cloudlut
