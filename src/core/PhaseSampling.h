#pragma once
// Random numbers and phase-function sampling for the Monte Carlo estimators: the path tracers of
// reference/ and the angular closure of bake/AngularClosure.h.
#include <cstdint>

#include <glm/vec3.hpp>

#include "core/Phase.h"

namespace cloudlut {

// Counter-seeded 64-bit generator (SplitMix64 steps): one independent stream per (a, b, c), so a
// parallel estimate that seeds one stream per work item is the same whatever the thread count.
class McRng {
 public:
  McRng(std::uint64_t a, std::uint64_t b, std::uint64_t c);
  std::uint64_t nextBits();
  double next() { return static_cast<double>(nextBits() >> 11) * 0x1.0p-53; }  // [0, 1)

 private:
  std::uint64_t state_;
};

// Exact sample of the cosine of the scattering angle for a phase function (rejection sampling
// from Henyey–Greenstein lobes).
double samplePhaseCosine(const Phase& phase, McRng& rng);

// A unit vector at angle acos(mu) from the unit vector d, at azimuth 2π·u about it.
glm::dvec3 rotateAbout(const glm::dvec3& d, double mu, double u);

// The direction after scattering from direction d by the phase function: the azimuth's uniform
// number drawn first, then the cosine (samplePhaseCosine). Written out in that order because a
// call's arguments are evaluated in an order the compiler chooses: as one call
// rotateAbout(d, samplePhaseCosine(phase, rng), rng.next()), GCC drew the azimuth first and
// Clang the cosine, so the two builds traced different photons from the same seed.
glm::dvec3 sampleScatteredDirection(const glm::dvec3& d, const Phase& phase, McRng& rng);

}  // namespace cloudlut
