#pragma once
// Radiance leaving the homogeneous unit sphere, tallied from forward photon tracing
// (traceForwardPhoton, SphereMonteCarlo.h) in bins of the scattering tables' angles: an
// estimator that shares nothing with the backward path tracer or the baker, so it checks both.
//
// Angles as in the tables (lut_formats/FORMAT.md, gatherTable in bake/MultipleScattering.cpp):
// the sun is toward l = +z; a surface point S = (sin θS, 0, cos θS) up to a rotation about l;
// the camera looks along v into the sphere, v = sin θv (cos φv f_x + sin φv f_y) − cos θv S
// with f_y = l × S / |l × S| and f_x = f_y × S; φv is folded to [0, π] (the sphere is mirror
// symmetric about the plane of S and l). A photon leaving at P along ω is the sample S = P,
// v = −ω.
//
// The mean radiance of a bin (per unit sun irradiance, sr⁻¹) is the power leaving through it
// over its area and projected solid angle:
//   L̄ = π · E[w · 1_bin] / (A · Ω⊥),  A = 2π (cos θS₀ − cos θS₁),
//   Ω⊥ = (φv₁ − φv₀) (sin² θv₁ − sin² θv₀)   (both mirror halves of φv),
// π being the power entering a unit sphere per unit irradiance.
#include <cstdint>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "core/Phase.h"

namespace cloudlut::reference {

struct ExitBin {
  double thetaS[2];  // radians, θS₀ < θS₁
  double thetaV[2];  // radians within [0, π/2]
  double phiV[2];    // radians within [0, π]
};

struct ExitBinRadiance {
  double radiance = 0;  // scattered light (every order ≥ 1), sr⁻¹ per unit sun irradiance
  double se = 0;        // its standard error
  long long hits = 0;   // photons that left through the bin
};

// Traces `photons` forward photons (blocks of kPathsPerBlock, block b seeded by (seed, b):
// the result does not depend on the number of threads) and tallies the bins (which may
// overlap). Throws std::invalid_argument for photons < 1.
std::vector<ExitBinRadiance> tallyExitRadiance(double sigma, const Phase& first, const Phase& later,
                                               const std::vector<ExitBin>& bins, long long photons,
                                               std::uint64_t seed);

// The same bin mean of a radiance function L(S, v) (l = +z) by the midpoint rule in n steps
// of cos θS, sin² θv and φv: uniform in exactly the measure above, so a table evaluated
// through this is comparable bin for bin.
double binMean(const ExitBin& bin, int n, const std::function<double(const glm::dvec3& S, const glm::dvec3& v)>& L);

// The dark side of the sphere, θS in [100°, 180°], in equal bands: nS of θS, nV of θv over
// [0, 90°] and nP of φv over [0, 180°] (nS·nV·nP bins, each band ≥ 1).
std::vector<ExitBin> darkSideBins(int nS, int nV, int nP);

}  // namespace cloudlut::reference
