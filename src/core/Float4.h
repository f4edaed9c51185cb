#pragma once
// Four floats as one SIMD value (GCC/Clang vector extension: SSE on x86-64, NEON on ARM), and
// the few operations the bake's hot loops need on it.
#include <cstdint>
#include <cstring>
#include <initializer_list>

namespace cloudlut {

typedef float Float4 __attribute__((vector_size(16)));
typedef std::int32_t Int4 __attribute__((vector_size(16)));
// Eight floats, for code compiled for AVX2 (target attribute) and chosen at run time.
typedef float Float8 __attribute__((vector_size(32)));

// 1 where the eight-lane AVX2 paths are compiled: GCC on x86-64 (each chosen at run time by
// cpuHasAvx2Lanes below). Clang rejects 32-byte vectors passed through the always-inlined
// helpers outside AVX code, so its builds (the sanitizer build) take the four-lane paths, which
// give the same bits.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CLOUDLUT_AVX2_LANES 1
#else
#define CLOUDLUT_AVX2_LANES 0
#endif

// Whether the eight-lane paths may run: compiled (CLOUDLUT_AVX2_LANES) and the processor has
// AVX2 (asked once). Every AVX2 kernel of the bake is chosen by this.
inline bool cpuHasAvx2Lanes() {
#if CLOUDLUT_AVX2_LANES
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
#else
  return false;
#endif
}

// The number of float lanes of the float vector type V: 4 for Float4, 8 for Float8.
template <class V>
constexpr int floatLanes() {
  return static_cast<int>(sizeof(V) / sizeof(float));
}

// GCC's -Wpsabi: passing a 32-byte vector (Float8) by value to or from a function not compiled
// for AVX would change the ABI, and GCC warns at such calls and adds the note "the ABI for
// passing parameters with 32-byte alignment has changed in GCC 4.6" where a function takes one.
// Here wide vectors are passed only between always-inlined helpers inside functions compiled
// with target("avx2"), so no such call is ever made. Templates that take wide vectors sit
// between these two macros (in any header); the files that instantiate them for Float8 are
// compiled with -Wno-psabi (CMakeLists.txt, the bake room), since GCC prints the note whatever
// the pragmas say.
#define CLOUDLUT_WIDE_VECTORS_BEGIN _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wpsabi\"")
#define CLOUDLUT_WIDE_VECTORS_END _Pragma("GCC diagnostic pop")

inline Float4 loadFloat4(const float* p) {
  Float4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline float sumFloat4(Float4 v) { return (v[0] + v[1]) + (v[2] + v[3]); }

// √x per lane, correctly rounded (IEEE 754), so equal to std::sqrt lane by lane; x ≥ 0.
inline Float4 sqrtFloat4(Float4 x) {
#if defined(__SSE__)
  return __builtin_ia32_sqrtps(x);
#else
  for (int k = 0; k < 4; ++k) x[k] = __builtin_sqrtf(x[k]);
  return x;
#endif
}

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

// Definitions of the three functions above, inline: they run in the innermost loops of the bake
// (the J_2 ray integrals, the stencils' locate), where a call per four lanes cost ~10% of them.
// exp and log are written once for any float vector (expLanes, logLanes): four lanes here, eight
// in the AVX2 paths (Float8), each lane by the same operations.
// Always inlined: instantiated for Float8 they run inside AVX2 functions only.
CLOUDLUT_WIDE_VECTORS_BEGIN
namespace float4_detail {
// ln 2 = kLn2Hi + kLn2Lo, kLn2Hi with few mantissa bits (n · kLn2Hi exact for |n| < 2^9).
constexpr float kLn2Hi = 0.693359375f, kLn2Lo = -2.12194440e-4f;
constexpr float kLog2e = 1.44269504088896341f;

inline Float4 splat(float v) { return Float4{v, v, v, v}; }
template <class V>
[[gnu::always_inline]] inline V splatLanes(float v) {
  return V{} + v;
}

// c[0]·x^(n−1) + … + c[n−1] by Horner's rule, per lane.
template <class V>
[[gnu::always_inline]] inline V horner(V x, std::initializer_list<float> c) {
  const float* k = c.begin();
  V p = splatLanes<V>(*k);
  for (++k; k != c.end(); ++k) p = p * x + *k;
  return p;
}

template <class T, class F>
[[gnu::always_inline]] inline T bitsAs(F f) {
  T t;
  static_assert(sizeof t == sizeof f, "same size");
  std::memcpy(&t, &f, sizeof t);
  return t;
}
inline Float4 fromBits(Int4 b) { return bitsAs<Float4>(b); }
inline Int4 toBits(Float4 f) { return bitsAs<Int4>(f); }

// expFloat4 and logFloat4 for a float vector V of any width (I: its int vector).
template <class V>
[[gnu::always_inline]] inline V expLanes(V x) {
  using I = decltype(x < x);
  const I under = x < -87.3f;  // −1 where e^x is below the normal range
  x = x < -87.3f ? splatLanes<V>(-87.3f) : x;
  // n = round(x / ln 2), as floor(x log2 e + 1/2) (conversion truncates toward zero)
  const V fx = x * kLog2e + 0.5f;
  V n = __builtin_convertvector(__builtin_convertvector(fx, I), V);
  n = n > fx ? n - 1.0f : n;
  const V r = (x - n * kLn2Hi) - n * kLn2Lo;
  // e^r = 1 + r + r² Q(r), Q by minimax on |r| ≤ ln 2 / 2
  const V q = horner(r, {1.9875691500e-4f, 1.3981999507e-3f, 8.3334519073e-3f,
                         4.1665795894e-2f, 1.6666665459e-1f, 5.0000001201e-1f});
  const V er = (q * (r * r) + r) + 1.0f;
  const I scale = (__builtin_convertvector(n, I) + 127) << 23;  // 2^n
  const V y = er * bitsAs<V>(scale);
  return under ? splatLanes<V>(0.0f) : y;
}

template <class V>
[[gnu::always_inline]] inline V logLanes(V x) {
  using I = decltype(x < x);
  const I bits = bitsAs<I>(x);
  I e = ((bits >> 23) & 0xff) - 126;                          // x = m 2^e, m ∈ [1/2, 1)
  V m = bitsAs<V>((bits & 0x007fffff) | 0x3f000000);
  const I low = m < 0.70710678118654752f;                     // m < √½: use 2m, e − 1
  e = low ? e - 1 : e;
  const V z = low ? (m + m) - 1.0f : m - 1.0f;                // z ∈ [√½ − 1, √2 − 1)
  const V p = horner(z, {7.0376836292e-2f, -1.1514610310e-1f, 1.1676998740e-1f,
                         -1.2420140846e-1f, 1.4249322787e-1f, -1.6668057665e-1f,
                         2.0000714765e-1f, -2.4999993993e-1f, 3.3333331174e-1f});
  const V z2 = z * z, fe = __builtin_convertvector(e, V);
  V y = z * z2 * p + fe * kLn2Lo;
  y = y - 0.5f * z2;
  return (z + y) + fe * kLn2Hi;
}
}  // namespace float4_detail
CLOUDLUT_WIDE_VECTORS_END

inline Float4 expFloat4(Float4 x) { return float4_detail::expLanes(x); }

inline Float4 logFloat4(Float4 x) { return float4_detail::logLanes(x); }

namespace float4_detail {
CLOUDLUT_WIDE_VECTORS_BEGIN
// atan2Float4 for a float vector V of any width.
template <class V>
[[gnu::always_inline]] inline V atan2Lanes(V y, V x) {
  using I = decltype(x < x);
  const V ax = x < 0.0f ? -x : x, ay = y < 0.0f ? -y : y;
  const I steep = ay > ax;
  const V hi = steep ? ay : ax, lo = steep ? ax : ay;
  const V a = lo / (hi > 0.0f ? hi : splatLanes<V>(1.0f));
  const V u = a * a;
  const V p = horner(u, {2.8498894535e-3f, -1.6068628058e-2f, 4.2691517621e-2f,
                         -7.5042940676e-2f, 1.0640934110e-1f, -1.4203643799e-1f,
                         1.9992619753e-1f, -3.3333072066e-1f, 1.0f});
  V r = a * p;
  r = steep ? 1.57079632679489662f - r : r;
  r = x < 0.0f ? 3.14159265358979324f - r : r;
  return y < 0.0f ? -r : r;
}
CLOUDLUT_WIDE_VECTORS_END
}  // namespace float4_detail

inline Float4 atan2Float4(Float4 y, Float4 x) { return float4_detail::atan2Lanes(y, x); }

}  // namespace cloudlut
