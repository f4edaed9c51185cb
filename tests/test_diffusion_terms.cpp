// The diffusion functions of the shared GLSL (lut_formats/glsl/cloudlut_shading.glsl, compiled
// here through GLM) against independent computations: the P1 field's scattered radiance by
// quadrature over the sphere, Marshak's exit coefficient from the boundary condition solved
// again, the δ-Eddington mean cosine of the Henyey–Greenstein phase function, and the share's limits.
#include <cmath>

#include <catch2/catch.hpp>
#include <glm/geometric.hpp>

#include "core/Glsl.h"

using namespace cloudlut;

namespace {

double henyeyGreenstein(double mu, double g) {
  const double d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) / (4.0 * M_PI * d * std::sqrt(d));
}

}  // namespace

TEST_CASE("diffusion: the P1 field's radiance toward a direction is the phase function's average of it", "[diffusion]") {
  // ∫ p(ω'·ω) (φ + 3 J·ω')/(4π) dω' by the midpoint rule in (cos θ, ϕ), for a field whose flux is
  // not along ω
  const double g = 0.757, phi = 1.3;
  const glm::dvec3 J(0.2, -0.35, 0.1), omega = glm::normalize(glm::dvec3(0.3, 0.8, -0.5));
  const int nMu = 4000, nPhi = 256;
  double sum = 0.0;
  for (int i = 0; i < nMu; ++i) {
    const double ct = -1.0 + (i + 0.5) * 2.0 / nMu, st = std::sqrt(1.0 - ct * ct);
    for (int k = 0; k < nPhi; ++k) {
      const double p = (k + 0.5) * 2.0 * M_PI / nPhi;
      const glm::dvec3 w(st * std::cos(p), st * std::sin(p), ct);
      sum += henyeyGreenstein(glm::dot(w, omega), g) * (phi + 3.0 * glm::dot(J, w)) / (4.0 * M_PI);
    }
  }
  const double quadrature = sum * (2.0 / nMu) * (2.0 * M_PI / nPhi);
  const float shader = glsl::diffusedRadiance(static_cast<float>(phi), glm::vec3(J), glm::vec3(omega),
                                               static_cast<float>(g));
  CHECK(shader == Approx(quadrature).epsilon(2e-3));
  // a flux larger than φ toward −ω cannot make the radiance negative
  CHECK(glsl::diffusedRadiance(0.1f, glm::vec3(omega) * -1.0f, glm::vec3(omega), 0.757f) == 0.0f);
}

TEST_CASE("diffusion: Marshak's exit coefficient solves the boundary condition", "[diffusion]") {
  for (const double D : {0.01, 0.1, 1.0, 7.0})
    for (const double h : {0.05, 0.3}) {
      // D·(φ − φf)/(h/2) = φf/2  ⇒  φf = φ·(2D/h)/(2D/h + 1/2); the flux out is φf/2
      const double phi = 2.0;
      const double face = phi * (2.0 * D / h) / (2.0 * D / h + 0.5);
      CHECK(glsl::marshakExitCoefficient(static_cast<float>(D), static_cast<float>(h)) * phi ==
            Approx(face / 2.0).epsilon(1e-5));
    }
}

TEST_CASE("diffusion: δ-Eddington keeps the Henyey–Greenstein phase function's mean cosine", "[diffusion]") {
  // f·δ + (1 − f)·HG(g*) must have the mean cosine g of HG(g)
  const double g = 0.757, f = glsl::deltaEddingtonForwardShare(static_cast<float>(g)),
               gs = glsl::deltaEddingtonAsymmetry(static_cast<float>(g));
  double m1 = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double mu = -1.0 + (i + 0.5) * 2.0 / n, w = henyeyGreenstein(mu, gs) * 2.0 * M_PI * 2.0 / n;
    m1 += w * mu;
  }
  CHECK(f + (1.0 - f) * m1 == Approx(g).epsilon(1e-4));
  CHECK(f == Approx(g * g));
  CHECK(glsl::diffusionCoefficient(2.0f, 0.0f) == Approx(1.0 / 6.0));
  CHECK(glsl::diffusionCoefficient(0.0f, 4.0f) == Approx(0.25));  // clear air: |D∇φ| = φ
}

TEST_CASE("diffusion: its share of the multiple light", "[diffusion]") {
  CHECK(glsl::diffusionShareOfMultiple(0.8f, 1.0f, -0.5f) == Approx(0.8));
  CHECK(glsl::diffusionShareOfMultiple(1.0f, 0.0f, -1.0f) == Approx(0.5));
  CHECK(glsl::diffusionShareOfMultiple(1.0f, 1.0f, 1.0f) == 0.0f);  // looking at the sun: the tables
  CHECK(glsl::diffusionShareOfMultiple(0.0f, 1.0f, 0.0f) == 0.0f);
  for (float mu = -1.0f; mu <= 1.0f; mu += 0.1f)
    for (float w = 0.0f; w <= 1.0f; w += 0.25f) {
      const float s = glsl::diffusionShareOfMultiple(1.0f, w, mu);
      CHECK(s >= 0.0f);
      CHECK(s <= 1.0f);
    }
}

TEST_CASE("diffusion: the weight of the cloud beside a point", "[diffusion]") {
  using glm::vec4;
  CHECK(glsl::cloudBesideWeight(vec4(0.0f), 8.0f) == 0.0f);                         // clear air around
  CHECK(glsl::cloudBesideWeight(vec4(8.0f, 9.0f, 20.0f, 8.0f), 8.0f) == Approx(1.0));  // inside a cloud
  // a particle at the side of a heap: the heap's columns on one side, clear air on the other
  CHECK(glsl::cloudBesideWeight(vec4(12.0f, 0.0f, 6.0f, 0.0f), 8.0f) == Approx((1.0 + 0.75) / 4.0));
  // a particle alone: the volume's rounding beside it (~10⁻³) against its own column weighs nothing
  CHECK(glsl::cloudBesideWeight(vec4(1e-3f), 5.0f) < 1e-3f);
  CHECK(glsl::cloudBesideWeight(vec4(0.005f), 0.0f) == Approx(0.5));  // the point's column floored at 0.01
  // each column counts once, whatever its order
  const vec4 c(3.0f, 0.5f, 7.0f, 1.5f);
  CHECK(glsl::cloudBesideWeight(c, 4.0f) == Approx(glsl::cloudBesideWeight(vec4(c.w, c.z, c.y, c.x), 4.0f)));
  CHECK(glsl::cloudBesideWeight(c, 4.0f) == Approx((0.75 + 0.125 + 1.0 + 0.375) / 4.0));
}
