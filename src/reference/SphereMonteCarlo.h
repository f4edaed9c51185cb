#pragma once
// Monte Carlo ground truth for the homogeneous unit sphere (particle space as in
// docs/ENGINE_GUIDE.md §2): the
// independent reference the scattering tables are judged against. It shares nothing with the
// baker beyond the geometry and phase functions of core/Glsl.h.
//
// Radiance (per unit sun irradiance, sr⁻¹) leaving the sphere at S toward a camera that looks
// along v (v·S < 0), sunlight propagating along -l, extinction σ (optical radius) everywhere in
// the sphere, no absorption:
//   single      = P1(v·l) · ∫_0^chord σ e^{-σt} e^{-σ d_sun(S + t v)} dt     (order 1)
//   multipleN   = orders 2 … N (N = 18 by default)
//   multipleAll = orders 2 … ∞
// Estimator: backward path tracing from S along v. Every segment takes a forced collision
// inside the sphere (truncated-exponential free flight, weight × (1 − e^{-σ·chord})); every
// vertex k connects to the sun (next-event estimation: P1 × closed-form sun transmittance),
// which tallies order k; the path continues with a direction sampled exactly from the later
// phase function (rejection sampling). Order k+1 is also estimated from vertex k along a
// direction sampled from P1 about l, and the two techniques are combined by multiple
// importance sampling, so the sharp sunward peak of P1 is sampled rather than hit by chance.
// Russian roulette ends paths of small weight without bias.
//
// Determinism: the paths of a query are split into fixed blocks of kPathsPerBlock; block b of
// row r draws from a generator seeded by (seed, r, b), and the block sums are combined in
// order, so the result does not depend on the number of threads.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/PhaseSampling.h"
#include "core/Progress.h"

namespace cloudlut::reference {

struct SphereMcSettings {
  Phase first = defaults::kFirstPhase;  // sunlight's first scattering
  Phase later = defaults::kLaterPhase;  // every later scattering
  long long paths = 100000; // per query
  std::uint64_t seed = 1;
  int splitOrder = 18;      // multipleN holds orders 2 … splitOrder
  double rouletteWeight = 0.05;  // paths lighter than this play Russian roulette
  int maxOrder = 0;              // > 0: stop paths after this order (multipleAll then holds
                                 // orders 2 … maxOrder only); 0 = no limit
};

struct SphereMcQuery {
  glm::dvec3 S;      // entry point (normalised by the estimator)
  glm::dvec3 v;      // view direction into the sphere (normalised)
  glm::dvec3 l;      // toward the sun (normalised)
  double sigma = 1;  // optical radius: extinction · radius · density scale
};

struct SphereMcEstimate {
  double single = 0, singleSe = 0;
  double multipleN = 0, multipleNSe = 0;
  double multipleAll = 0, multipleAllSe = 0;
  double meanVertices = 0;  // mean path length (scattering vertices per path)
};

inline constexpr long long kPathsPerBlock = 2048;

// Estimates every query; query i is row i of the determinism contract. Parallel (oneTBB).
std::vector<SphereMcEstimate> estimateSphereRadiance(const std::vector<SphereMcQuery>& queries,
                                                     const SphereMcSettings& settings,
                                                     const ProgressFn& progress = {});

// The generator and the phase sampling are core/PhaseSampling.h's.
using cloudlut::McRng;
using cloudlut::samplePhaseCosine;

// One forward (analog) photon: it enters uniformly over the sun-facing disk along −l, its
// first collision is forced (weight = 1 − e^{−σ·chord}, the rest crosses unscattered), and it
// scatters (first phase, then later phase) until it leaves the sphere.
struct ForwardPhoton {
  double weight = 0;             // the scattered share it carries
  double unscatteredWeight = 0;  // the share that crossed without a collision (exact)
  int order = 0;                 // scatterings before it left
  glm::dvec3 exitPoint{0.0};     // on the unit sphere
  glm::dvec3 exitDirection{0.0}; // unit
};
ForwardPhoton traceForwardPhoton(double sigma, const Phase& first, const Phase& later, McRng& rng);

// Shares of the incident power (π for unit irradiance) leaving the sphere, by order, from
// forward (analog) photon tracing: photons enter uniformly over the cross-section.
struct PhotonShares {
  double unscattered = 0;          // exact expectation per photon (no noise)
  std::vector<double> byOrder;     // byOrder[k] = share escaping after exactly k scatterings, k ≥ 1
  double beyond = 0;               // escaping after more than byOrder.size() - 1 scatterings
  double total = 0;                // sum of everything above (1 for a non-absorbing sphere)
  double standardError = 0;        // standard error of any single share (≤ 0.5/√photons)
};
PhotonShares photonTraceSphere(double sigma, const Phase& first, const Phase& later,
                               long long photons, std::uint64_t seed, int maxOrder = 18);

// The same shares from the backward estimator above, integrated over the sphere surface
// (S uniform) and the outgoing hemisphere (cosine-weighted): share = 4π·E[L]. An end-to-end
// check of the backward estimator's normalisation against photonTraceSphere.
struct BackwardShares {
  double single = 0, singleSe = 0;
  double multipleN = 0, multipleNSe = 0;
  double multipleAll = 0, multipleAllSe = 0;
};
BackwardShares integrateBackwardShares(double sigma, const SphereMcSettings& settings,
                                       long long samples);

// Closed-form share of the incident power crossing the sphere unscattered:
// (1 − e^{−2σ}(1 + 2σ)) / (2σ²).
double unscatteredShare(double sigma);

}  // namespace cloudlut::reference
