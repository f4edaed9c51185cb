// The bake's four-lane transcendental functions (bake/Float4.h) against the C library's double
// precision functions, over sweeps that cover every branch (octants, signs, exponent ranges).
#include <catch2/catch.hpp>

#include <cmath>

#include "core/Float4.h"

using namespace cloudlut;

namespace {
// Largest relative error of f4 against f over n points of [a, b], four at a time.
template <class F4, class F>
double worstRelative(F4 f4, F f, double a, double b, int n) {
  double worst = 0.0;
  for (int i = 0; i < n; i += 4) {
    Float4 x;
    for (int k = 0; k < 4; ++k) x[k] = static_cast<float>(a + (b - a) * (i + k) / (n - 1));
    const Float4 y = f4(x);
    for (int k = 0; k < 4; ++k) {
      const double ref = f(static_cast<double>(x[k]));
      if (ref != 0.0) worst = std::max(worst, std::abs(static_cast<double>(y[k]) - ref) / std::abs(ref));
    }
  }
  return worst;
}
}  // namespace

TEST_CASE("Float4: exp and log per lane within a few ulp of libm", "[float4]") {
  const auto e4 = [](Float4 x) { return expFloat4(x); };
  const auto l4 = [](Float4 x) { return logFloat4(x); };
  CHECK(worstRelative(e4, [](double x) { return std::exp(x); }, -80.0, 80.0, 200000) < 4e-7);
  CHECK(worstRelative(l4, [](double x) { return std::log(x); }, 1e-30, 1e-20, 20000) < 4e-7);
  CHECK(worstRelative(l4, [](double x) { return std::log(x); }, 1.5, 1e6, 200000) < 4e-7);
  // Below the normal range e^x is 0.
  CHECK(expFloat4(Float4{-100.0f, -90.0f, -88.0f, 0.0f})[0] == 0.0f);
  CHECK(expFloat4(Float4{-100.0f, -90.0f, -88.0f, 0.0f})[3] == 1.0f);
}

TEST_CASE("Float4: atan2 per lane in every octant within 3e-7 of libm", "[float4]") {
  double worst = 0.0;
  const int n = 4096;
  for (int i = 0; i < n; i += 4) {
    Float4 y, x;
    for (int k = 0; k < 4; ++k) {
      const double a = -3.14159265358979 + 2.0 * 3.14159265358979 * (i + k + 0.5) / n;
      const double r = 0.001 + 37.0 * (i + k) / n;
      x[k] = static_cast<float>(r * std::cos(a));
      y[k] = static_cast<float>(r * std::sin(a));
    }
    const Float4 t = atan2Float4(y, x);
    for (int k = 0; k < 4; ++k) {
      const double ref = std::atan2(static_cast<double>(y[k]), static_cast<double>(x[k]));
      worst = std::max(worst, std::abs(static_cast<double>(t[k]) - ref) / std::max(std::abs(ref), 1e-3));
    }
  }
  CHECK(worst < 3e-7);
  // The axes and the origin.
  const Float4 t = atan2Float4(Float4{0.0f, 1.0f, 0.0f, -1.0f}, Float4{0.0f, 0.0f, -1.0f, 0.0f});
  CHECK(t[0] == 0.0f);
  CHECK(t[1] == Approx(1.5707963).epsilon(1e-7));
  CHECK(t[2] == Approx(3.1415927).epsilon(1e-7));
  CHECK(t[3] == Approx(-1.5707963).epsilon(1e-7));
}

TEST_CASE("Float4: sqrt per lane equals std::sqrt bit for bit", "[float4]") {
  for (int i = 0; i < 100000; i += 4) {
    Float4 x;
    for (int k = 0; k < 4; ++k)
      x[k] = static_cast<float>(std::ldexp(1.0 + (i + k) * 1e-5, (i + k) % 200 - 100));
    const Float4 r = sqrtFloat4(x);
    for (int k = 0; k < 4; ++k) REQUIRE(r[k] == std::sqrt(x[k]));
  }
  const Float4 edge = sqrtFloat4(Float4{0.0f, 1.0f, 4.0f, 1e-40f});
  CHECK(edge[0] == 0.0f);
  CHECK(edge[1] == 1.0f);
  CHECK(edge[2] == 2.0f);
  CHECK(edge[3] == std::sqrt(1e-40f));
}
