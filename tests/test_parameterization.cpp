// The shared parameterization (lut_formats/glsl/cloudlut_geometry.glsl) through GLM:
// geometry → LUT angles → geometry round trips, including the poles and grazing rays.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "bake/ScatteringBaker.h"
#include "bake/SingleScattering.h"
#include "core/Glsl.h"
#include "core/Table4D.h"

using namespace cloudlut::glsl;

namespace {
constexpr float kPi = 3.14159265358979f;

float distance3(vec3 a, vec3 b) { return length(a - b); }

// Rebuilds (S, v) from optical-depth angles, independently of opticalDepthAngles.
void geometryFromAngles(vec4 a, vec3& S, vec3& v) {
  S = sphericalPoint(a.x, a.y);
  v = frameDirection(tangentX(a.x, a.y), tangentY(a.x), S, a.z, a.w);
}
}  // namespace

TEST_CASE("tangent frame is orthonormal everywhere, poles included", "[parameterization]") {
  for (float theta : {0.0f, 1e-4f, 0.7f, kPi / 2, kPi - 1e-4f, kPi}) {
    for (float phi : {0.0f, 1.0f, 3.0f, 2 * kPi}) {
      const vec3 S = sphericalPoint(phi, theta), x = tangentX(phi, theta), y = tangentY(phi);
      CHECK(std::fabs(length(x) - 1.0f) < 1e-6f);
      CHECK(std::fabs(length(y) - 1.0f) < 1e-6f);
      CHECK(std::fabs(dot(x, y)) < 1e-6f);
      CHECK(std::fabs(dot(x, S)) < 1e-6f);
      CHECK(std::fabs(dot(y, S)) < 1e-6f);
    }
  }
}

TEST_CASE("optical-depth parameterization round trip: geometry -> angles -> geometry", "[parameterization]") {
  std::mt19937 rng(42);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    // random entry point, with a share of exact poles, and random inward direction, with a
    // share of exactly grazing and exactly normal rays
    float theta = kPi * u(rng);
    if (i % 10 == 0) theta = 0.0f;
    if (i % 10 == 1) theta = kPi;
    const vec3 S = sphericalPoint(2 * kPi * u(rng), theta);
    vec3 w = normalize(vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    w = w - dot(w, S) * S;  // tangent component
    if (length(w) < 1e-3f) continue;
    w = normalize(w);
    float tv = 0.5f * kPi * u(rng);
    if (i % 7 == 0) tv = 0.5f * kPi;  // grazing
    if (i % 7 == 1) tv = 0.0f;        // through the centre
    const vec3 v = std::sin(tv) * w - std::cos(tv) * S;
    const vec4 a = opticalDepthAngles(S, v);
    REQUIRE(std::isfinite(a.x));
    REQUIRE(std::isfinite(a.y));
    REQUIRE(std::isfinite(a.z));
    REQUIRE(std::isfinite(a.w));
    REQUIRE(a.x >= 0.0f);
    REQUIRE(a.x < 2 * kPi + 1e-6f);
    REQUIRE(a.w <= 0.5f * kPi + 1e-6f);
    vec3 S2, v2;
    geometryFromAngles(a, S2, v2);
    REQUIRE(distance3(S, S2) < 2e-5f);
    REQUIRE(distance3(v, v2) < 2e-3f);  // acos near θv = 0 loses digits; the ray is the same
    const vec4 x = opticalDepthAxes(S, v);
    for (int k = 0; k < 4; ++k) REQUIRE((x[k] >= 0.0f && x[k] <= 1.0f));
    ++checked;
  }
  CHECK(checked > 19000);
}

TEST_CASE("scattering angles match the optical-depth frame when the sun is the pole", "[parameterization]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const vec3 l(0.0f, 0.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const float thetaS = kPi * (0.01f + 0.98f * u(rng)), phiV = 2 * kPi * u(rng), thetaV = 0.5f * kPi * u(rng);
    const vec3 S = sphericalPoint(0.0f, thetaS);
    const vec3 v = frameDirection(tangentX(0.0f, thetaS), tangentY(0.0f), S, phiV, thetaV);
    const vec3 a = scatteringAngles(S, v, l);
    REQUIRE(std::fabs(a.x - thetaS) < 1e-4f);
    REQUIRE(std::fabs(std::remainder(a.y - phiV, 2 * kPi)) < 2e-3f + (thetaV < 0.01f ? 1.0f : 0.0f));
    REQUIRE(std::fabs(a.z - thetaV) < 2e-3f);
  }
}

TEST_CASE("scattering angles are invariant under rotation about the sun axis", "[parameterization]") {
  // The light field of a sphere is symmetric about l: rotating S and v together about l must
  // not change (θS, φv, θv), even for an arbitrary l and at the poles' neighbourhood.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int i = 0; i < 2000; ++i) {
    const vec3 l = normalize(vec3(u(rng), u(rng), u(rng)));
    const vec3 S = normalize(vec3(u(rng), u(rng), u(rng)));
    vec3 v = normalize(vec3(u(rng), u(rng), u(rng)));
    if (dot(v, S) > -0.05f) v = normalize(v - 2.0f * std::max(dot(v, S), 0.0f) * S - 0.1f * S);
    if (dot(v, S) >= 0.0f || std::fabs(dot(S, l)) > 0.999f) continue;
    const float ang = 3.0f * u(rng);
    auto rot = [&](vec3 p) {  // Rodrigues rotation about l
      return p * std::cos(ang) + cross(l, p) * std::sin(ang) + l * dot(l, p) * (1.0f - std::cos(ang));
    };
    const vec3 a = scatteringAngles(S, v, l), b = scatteringAngles(rot(S), rot(v), l);
    REQUIRE(std::fabs(a.x - b.x) < 1e-3f);
    REQUIRE(std::fabs(std::remainder(a.y - b.y, 2 * kPi)) < 5e-3f + (a.z < 0.01f ? 7.0f : 0.0f));
    REQUIRE(std::fabs(a.z - b.z) < 1e-3f);
  }
}

TEST_CASE("texture coordinates hit texel centres at both ends of an axis", "[parameterization]") {
  CHECK(lutTexCoord(0.0f, 32.0f) == Approx(0.5f / 32.0f));
  CHECK(lutTexCoord(1.0f, 32.0f) == Approx(31.5f / 32.0f));
  CHECK(lutTexCoord(-3.0f, 32.0f) == Approx(0.5f / 32.0f));
  CHECK(lutTexCoord(0.5f, 3.0f) == Approx(0.5f));
  CHECK(densityAxis(1.0f / 16.0f, -4.0f, 3.0f) == Approx(0.0f));
  CHECK(densityAxis(8.0f, -4.0f, 3.0f) == Approx(1.0f));
  CHECK(densityAxis(1.0f, -4.0f, 3.0f) == Approx(4.0f / 7.0f));
}

TEST_CASE("folded azimuth and the density axis interpolated linearly in rho", "[parameterization]") {
  // mirroredAzimuth: φ and 2π − φ share a node; [0, π] is left alone
  for (float phi : {0.0f, 0.7f, 3.0f, 3.1415f})
    CHECK(mirroredAzimuth(phi) == Approx(phi));
  CHECK(mirroredAzimuth(4.0f) == Approx(2.0f * 3.14159265f - 4.0f));
  CHECK(mirroredAzimuth(6.28f) == Approx(0.0031853f).margin(1e-5));
  // densityAxisLinearInRho: at the nodes it is densityAxis; between two nodes the weight of the
  // upper one is (ρ − ρ_i)/(ρ_{i+1} − ρ_i), written out here from the node densities.
  const float sMin = -4.0f, sMax = 3.0f, n = 15.0f;
  for (int i = 0; i < 15; ++i) {
    const float rho = std::exp2(sMin + 0.5f * static_cast<float>(i));
    CHECK(densityAxisLinearInRho(rho, sMin, sMax, n) == Approx(densityAxis(rho, sMin, sMax)).margin(1e-5));
  }
  for (float s : {-3.9f, -1.2f, 0.3f, 2.8f}) {
    const float lo = std::floor(s * 2.0f) / 2.0f, rho = std::exp2(s);
    const float w = (rho - std::exp2(lo)) / (std::exp2(lo + 0.5f) - std::exp2(lo));
    const float x = ((lo - sMin) * 2.0f + w) / (n - 1.0f);
    CHECK(densityAxisLinearInRho(rho, sMin, sMax, n) == Approx(x).margin(1e-5));
  }
  CHECK(densityAxisLinearInRho(100.0f, sMin, sMax, n) == Approx(1.0f));
  CHECK(densityAxisLinearInRho(1e-4f, sMin, sMax, n) == Approx(0.0f));
  // scatteringAxes: a folded table's φv axis is mirroredAzimuth(φv)/π, an unfolded one φv/2π; a
  // view mirrored about the plane of S and l lands on the same folded fraction.
  const glm::vec3 S(0.6f, 0.0f, 0.8f), l(0.0f, 0.0f, 1.0f);
  const glm::vec3 v = glm::normalize(glm::vec3(-0.5f, 0.4f, -0.6f)), vm(v.x, -v.y, v.z);
  const glm::vec4 a = scatteringAxes(S, v, l, 1.0f, glm::vec4(-4.0f, 3.0f, 0.0f, 1.0f), 15.0f);
  const glm::vec4 b = scatteringAxes(S, vm, l, 1.0f, glm::vec4(-4.0f, 3.0f, 0.0f, 1.0f), 15.0f);
  const glm::vec4 c = scatteringAxes(S, v, l, 1.0f, glm::vec4(-4.0f, 3.0f, 0.0f, 0.0f), 15.0f);
  const glm::vec4 d = scatteringAxes(S, vm, l, 1.0f, glm::vec4(-4.0f, 3.0f, 0.0f, 0.0f), 15.0f);
  CHECK(a.y == Approx(b.y).margin(1e-5));
  CHECK(c.y + d.y == Approx(1.0f).margin(1e-5));
  CHECK(a.y == Approx(2.0f * std::min(c.y, d.y)).margin(1e-5));
  // layout 2 (linear in ρ) changes only the density fraction
  const glm::vec4 e = scatteringAxes(S, v, l, 1.5f, glm::vec4(-4.0f, 3.0f, 0.0f, 3.0f), 15.0f);
  CHECK(e.y == Approx(a.y));
  CHECK(e.w == Approx(densityAxisLinearInRho(1.5f, -4.0f, 3.0f, 15.0f)));
}

TEST_CASE("concentrated axes: the nodes, their inverse, and the theta_s concentration the baker picks", "[parameterization]") {
  // y = 1/2 + sinh(w (x − 1/2)) / (2 sinh(w/2)) written out here, not through the shared GLSL
  for (double w : {0.0, 3.0, 7.0, 12.0})
    for (int i = 0; i <= 40; ++i) {
      const double x = i / 40.0;
      const double y = w > 0 ? 0.5 + std::sinh(w * (x - 0.5)) / (2.0 * std::sinh(0.5 * w)) : x;
      CHECK(concentratedFraction(static_cast<float>(x), static_cast<float>(w)) == Approx(y).margin(2e-6));
      CHECK(concentratedAxis(static_cast<float>(y), static_cast<float>(w)) == Approx(x).margin(2e-5));
      cloudlut::Axis a{"theta_s", "rad", 0.0, kPi, 41, false, w};
      CHECK(a.value(i) == Approx(kPi * y).margin(1e-5));
    }
  // The scattering axes put θS through the inverse: a table node's geometry lands on its node.
  for (int n : {9, 16, 24, 32, 64}) {
    const double w = cloudlut::bake::sunZenithWarp(n);
    const double uniform = kPi / static_cast<double>(n - 1);
    const double pole = w > 0 ? uniform * 0.5 * w / std::tanh(0.5 * w) : uniform;
    INFO(n << " nodes: warp " << w << ", pole spacing " << pole * 180 / kPi << " deg");
    CHECK(w <= 7.0);
    CHECK((pole <= 21.0 / 180.0 * kPi + 1e-9 || w == 0.0));
    if (n >= 32) CHECK(w == 7.0);
    if (n <= 9) CHECK(w == 0.0);
    cloudlut::Axis a{"theta_s", "rad", 0.0, kPi, n, false, w};
    for (int i = 0; i < n; ++i) {
      const auto node = cloudlut::bake::scatteringNode(a.value(i), 0.3, 0.4);
      const glm::vec4 x = scatteringAxes(glm::vec3(node.S), glm::vec3(node.v), glm::vec3(node.l), 1.0f,
                                         glm::vec4(0.0f, 1.0f, static_cast<float>(w), 0.0f), 2.0f);
      CHECK(x.x * static_cast<float>(n - 1) == Approx(i).margin(2e-3));
    }
  }
}

TEST_CASE("phase functions integrate to one over the sphere", "[parameterization][phase]") {
  // Independent quadrature: composite Simpson in mu on a graded grid, 2π ∫ p(mu) dmu = 1.
  auto integrate = [](auto p) {
    const int n = 200000;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
      const double t = static_cast<double>(i) / n;
      const double mu = 1.0 - 2.0 * t * t;  // clusters samples at the forward peak
      const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
      sum += w * p(static_cast<float>(mu)) * 4.0 * t;  // dmu = -4 t dt
    }
    return 2.0 * 3.14159265358979 * sum / (3.0 * n);
  };
  CHECK(integrate([](float mu) { return phaseHenyeyGreenstein(mu, 0.9f); }) == Approx(1.0).epsilon(2e-3));
  CHECK(integrate([](float mu) { return phaseCornetteShanks(mu, 0.9f); }) == Approx(1.0).epsilon(2e-3));
  CHECK(integrate([](float mu) { return phaseCornetteShanks(mu, 0.7f); }) == Approx(1.0).epsilon(2e-3));
  CHECK(integrate([](float mu) { return phaseJendersieDeon(mu, jendersieDeonParameters(10.0f)); }) == Approx(1.0).epsilon(5e-3));
}

TEST_CASE("Jendersie-d'Eon parameters follow the published fit", "[parameterization][phase]") {
  // The fit of Jendersie & d'Eon (2023), evaluated here in double from the published constants
  // (seed 000 quotes it with a typo in w's last constant, -0.664888 for -0.665888).
  for (const double d : {5.0, 10.0, 20.0, 50.0}) {
    const double gHg = std::exp(-0.0990567 / (d - 1.67154));
    const double gD = std::exp(-2.20679 / (d + 3.91029) - 0.428934);
    const double alpha = std::exp(3.62489 - 8.29288 / (d + 5.52825));
    const double w = std::exp(-0.599085 / (d - 0.641583) - 0.665888);
    const vec4 jd = jendersieDeonParameters(static_cast<float>(d));
    INFO("d = " << d << " um");
    CHECK(jd.x == Approx(gHg).epsilon(1e-5));
    CHECK(jd.y == Approx(gD).epsilon(1e-5));
    CHECK(jd.z == Approx(alpha).epsilon(1e-5));
    CHECK(jd.w == Approx(w).epsilon(1e-5));
    // The phase itself: (1 - w) HG(g_HG) + w Draine(g_D, alpha), written out here, at a few angles.
    const auto hg = [](double mu, double g) {
      return (1.0 - g * g) / (4.0 * 3.14159265358979 * std::pow(1.0 + g * g - 2.0 * g * mu, 1.5));
    };
    for (const double mu : {1.0, 0.9, 0.0, -1.0}) {
      const double draine = hg(mu, gD) * (1.0 + alpha * mu * mu) / (1.0 + alpha * (1.0 + 2.0 * gD * gD) / 3.0);
      const double expected = (1.0 - w) * hg(mu, gHg) + w * draine;
      // at mu = 1 the float GLSL loses digits in 1 + g^2 - 2g = (1 - g)^2 (0.5% at d = 50)
      CHECK(phaseJendersieDeon(static_cast<float>(mu), jd) == Approx(expected).epsilon(mu == 1.0 ? 1e-2 : 2e-3));
    }
  }
  // At d = 10 um the published fit gives w = 0.4819 (the typo would give 0.4824) and a forward
  // peak of about 586 sr^-1.
  const vec4 jd10 = jendersieDeonParameters(10.0f);
  CHECK(jd10.w == Approx(0.4819).margin(1e-4));
  CHECK(phaseJendersieDeon(1.0f, jd10) == Approx(586.0f).epsilon(0.01));
}
