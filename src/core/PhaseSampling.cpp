#include "core/PhaseSampling.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/Glsl.h"

namespace cloudlut {

namespace {

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// Henyey–Greenstein cosine by inversion of its cumulative distribution, u ∈ [0, 1).
double sampleHg(double g, double u) {
  if (std::abs(g) < 1e-5) return 1.0 - 2.0 * u;
  const double s = (1.0 - g * g) / (1.0 - g + 2.0 * g * u);
  return std::clamp((1.0 + g * g - s * s) / (2.0 * g), -1.0, 1.0);
}

}  // namespace

McRng::McRng(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  state_ = mix64(a + 0x9e3779b97f4a7c15ULL);
  state_ = mix64(state_ ^ (b * 0xd1b54a32d192ed03ULL + 0x632be59bd9b4e019ULL));
  state_ = mix64(state_ ^ (c * 0xaef17502108ef2d9ULL + 0x1bd11bdaa9fc1a22ULL));
}

std::uint64_t McRng::nextBits() {
  state_ += 0x9e3779b97f4a7c15ULL;
  return mix64(state_);
}

double samplePhaseCosine(const Phase& phase, McRng& rng) {
  switch (phase.kind) {
    case PhaseKind::HenyeyGreenstein: return sampleHg(phase.param, rng.next());
    case PhaseKind::CornetteShanks:
      // Cornette–Shanks = HG · 3(1 + mu²)/(2(2 + g²)): accept an HG sample with (1 + mu²)/2.
      for (;;) {
        const double mu = sampleHg(phase.param, rng.next());
        if (2.0 * rng.next() < 1.0 + mu * mu) return mu;
      }
    case PhaseKind::JendersieDeon: {
      const glm::vec4 p = glsl::jendersieDeonParameters(phase.param);
      if (rng.next() >= static_cast<double>(p.w)) return sampleHg(static_cast<double>(p.x), rng.next());
      // Draine lobe = HG(g_D) · (1 + α mu²) / norm: accept with (1 + α mu²) / (1 + α).
      const double alpha = static_cast<double>(p.z);
      for (;;) {
        const double mu = sampleHg(static_cast<double>(p.y), rng.next());
        if (rng.next() * (1.0 + alpha) < 1.0 + alpha * mu * mu) return mu;
      }
    }
    case PhaseKind::Isotropic: break;
  }
  return 1.0 - 2.0 * rng.next();
}

glm::dvec3 sampleScatteredDirection(const glm::dvec3& d, const Phase& phase, McRng& rng) {
  const double azimuth = rng.next();
  const double mu = samplePhaseCosine(phase, rng);
  return rotateAbout(d, mu, azimuth);
}

glm::dvec3 rotateAbout(const glm::dvec3& d, double mu, double u) {
  const glm::dvec3 a = std::abs(d.x) < 0.7 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(d, a));
  const glm::dvec3 b = glm::cross(d, t);
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  const double phi = 2.0 * 3.14159265358979323846 * u;
  return glm::normalize(mu * d + s * (std::cos(phi) * t + std::sin(phi) * b));
}

}  // namespace cloudlut
