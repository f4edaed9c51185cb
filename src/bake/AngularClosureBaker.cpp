#include "bake/AngularClosureBaker.h"

#include <algorithm>
#include <cmath>
#include <atomic>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "core/Glsl.h"
#include "core/LastMatter.h"
#include "core/OwnSunDepth.h"
#include "core/PhaseSampling.h"
#include "core/TableLookup.h"

namespace cloudlut::bake {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr long long kMaxEventsPerPhoton = 10'000'000;  // a guard: ρ = 8 paths take ~10⁴

// Point i of n on a Fibonacci sphere (unit).
glm::dvec3 fibonacciDirection(int i, int n) {
  const double z = 1.0 - 2.0 * (i + 0.5) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = i * 2.399963229728653;  // golden angle, rad
  return {r * std::cos(phi), r * std::sin(phi), z};
}

void orthonormalFrame(const glm::dvec3& d, glm::dvec3& e1, glm::dvec3& e2) {
  const glm::dvec3 a = std::abs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  e1 = glm::normalize(glm::cross(d, a));
  e2 = glm::cross(d, e1);
}

int muBin(double mu, int bins) { return std::clamp(static_cast<int>((mu + 1.0) * 0.5 * bins), 0, bins - 1); }

// Highest order the table holds (orders 2 … N), or no limit when converged.
long long maxOrderOf(const Table4D& multiple) {
  const nlohmann::json& orders = multiple.parameters().value("orders", nlohmann::json("converged"));
  return orders.is_number_integer() ? orders.get<long long>() : kMaxEventsPerPhoton;
}

struct Tally {
  std::vector<double> power, power2;  // Monte Carlo: Σ w and Σ w² per bin (orders 2 … N)
  std::vector<double> model;          // the own-term model's power per bin
};

// Forward photons through the reference particle of density scale rho (optical radius
// σ = sigma·rho), lit along −l: the power (π per unit irradiance over the disc, shared equally)
// that leaves after 2 … maxOrder scatterings, by exit direction.
void tracePhotons(Tally& t, const ReferenceParticle& particle, double sigma, const glm::dvec3& l, const Phase& first,
                  const Phase& later, long long photons, long long maxOrder, std::uint64_t seed, std::uint64_t task,
                  int bins) {
  glm::dvec3 e1, e2;
  orthonormalFrame(l, e1, e2);
  const double w = kPi / static_cast<double>(photons);
  for (long long k = 0; k < photons; ++k) {
    McRng rng(seed, task, static_cast<std::uint64_t>(k));
    double b1, b2;
    do {
      b1 = 2.0 * rng.next() - 1.0;
      b2 = 2.0 * rng.next() - 1.0;
    } while (b1 * b1 + b2 * b2 >= 1.0);
    glm::dvec3 p = b1 * e1 + b2 * e2 + std::sqrt(1.0 - b1 * b1 - b2 * b2) * l;  // on the sunlit side
    glm::dvec3 d = -l;
    long long order = 0;
    for (long long events = 0; events < kMaxEventsPerPhoton; ++events) {
      p += d * (-std::log(1.0 - rng.next()) / sigma);  // delta tracking, majorant σ (ρ̂ ≤ 1)
      if (glm::dot(p, p) >= 1.0) break;
      if (rng.next() >= static_cast<double>(particle.density(glm::vec3(p)))) continue;  // null collision
      if (++order > maxOrder) break;
      d = sampleScatteredDirection(d, order == 1 ? first : later, rng);
    }
    if (order < 2 || order > maxOrder) continue;
    const int b = muBin(glm::dot(d, l), bins);
    t.power[b] += w;
    t.power2[b] += w * w;
  }
}

// The own-term model's power by exit direction −v: per μ bin, the mean over the view directions v
// in it of Σ over the chords of the disc facing v of (1 − e^{−τ}) J̄M(S, v, l, ρT̄) · C dA, with C
// the own core shadow at the chord's mean scattering point x̄ (ownCoreShadow: the particle's own
// τ toward the sun there, ownSunOpticalDepth with the table's outerThird, against the
// homogeneous sphere's; later-phase asymmetry g, at most s.ownCoreShadowMax) (particle.frag.glsl's
// own term without its sunlight factor, 1 for an isolated particle), times the bin's exact solid
// angle 4π/bins (a bin's count of Fibonacci directions varies with l by ±10%, which summing them
// would pass into K).
void integrateModel(Tally& t, const Table4D& od, float outerThird, const Table4D& multiple, float rho,
                    const glm::dvec3& l, float g, const AngularClosureSettings& s) {
  const float sigma = static_cast<float>(unitOpticalRadius(od));
  const ScatteringStorage storage = scatteringStorage(multiple);
  const float rhoMin = std::exp2(scatteringAxesRecord(multiple).x);
  const int n = s.discSide;
  const double dA = (2.0 / n) * (2.0 / n), binSolidAngle = 4.0 * kPi / s.muBins;
  const glm::vec3 lf(l);
  std::vector<double> sums(static_cast<std::size_t>(s.muBins), 0.0);
  std::vector<int> counts(static_cast<std::size_t>(s.muBins), 0);
  for (int iv = 0; iv < s.viewDirections; ++iv) {
    const glm::dvec3 v = fibonacciDirection(iv, s.viewDirections);
    glm::dvec3 e1, e2;
    orthonormalFrame(v, e1, e2);
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double c1 = -1.0 + (i + 0.5) * 2.0 / n, c2 = -1.0 + (j + 0.5) * 2.0 / n;
        const double b2 = c1 * c1 + c2 * c2;
        if (b2 >= 1.0) continue;
        const glm::vec3 S(glm::normalize(c1 * e1 + c2 * e2 - std::sqrt(1.0 - b2) * v));
        const OpticalDepthSample chord = lookupOpticalDepth(od, S, glm::vec3(v), rho);
        const float rhoChord = rho * chord.meanDensity;
        const float stored = sampleScattering(multiple, S, glm::vec3(v), lf, std::max(rhoChord, rhoMin)) *
                             std::min(rhoChord / rhoMin, 1.0f);
        float shadow = 1.0f;
        if (s.ownCoreShadow) {
          // at the chord's mean scattering point x̄ (meanScatteringShare, as particle.frag.glsl)
          const float share = glsl::meanScatteringShare(chord.firstMatter, lookupLastMatter(od, S, glm::vec3(v)),
                                                        chord.opticalDepth);
          const glm::vec3 x = S + share * chord.chordLength * glm::vec3(v);
          shadow = glsl::ownCoreShadow(ownSunOpticalDepth(od, outerThird, x, lf, rho),
                                       glsl::homogeneousOwnSunDepth(x, lf, rhoChord, sigma), g, s.ownCoreShadowMax);
        }
        sum += shadow * scatteringFromStored(storage, stored, chord.opticalDepth);
      }
    const auto b = static_cast<std::size_t>(muBin(-glm::dot(v, l), s.muBins));
    sums[b] += sum * dA;
    ++counts[b];
  }
  for (std::size_t b = 0; b < sums.size(); ++b)
    if (counts[b] > 0) t.model[b] += sums[b] / counts[b] * binSolidAngle;
}

}  // namespace

std::optional<AngularClosure> computeAngularClosure(const Table4D& od, const Table4D& multiple, const ReferenceParticle& particle,
                                     const Phase& first, const Phase& later, const AngularClosureSettings& s,
                                     const ProgressFn& progress) {
  if (s.densityNodes < 1 || s.densityNodes > kMaxAngularClosureAxis || s.muBins < 1 ||
      s.muBins > kMaxAngularClosureAxis || s.sunDirections < 1 ||
      s.photonsPerDirection < 1 || s.viewDirections < 1 || s.discSide < 1 || !(s.log2RhoStep > 0.0f) ||
      !(s.ownCoreShadowMax >= 1.0f && s.ownCoreShadowMax <= kMaxOwnCoreShadowMax))
    throw std::invalid_argument("angular closure: settings out of range");
  float outerThird = 0.0f;  // how the sun volume lays the own chord
  try {
    outerThird = chordOuterThird(od);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("angular closure: optical_depth's ") + e.what());
  }
  const double sigma = unitOpticalRadius(od);
  const float g = phaseMeanCosine(later);
  const long long maxOrder = maxOrderOf(multiple);
  const auto rhoOf = [&](int node) { return std::exp2(s.log2RhoFirst + s.log2RhoStep * static_cast<float>(node)); };
  int nodes = 0;
  while (nodes < s.densityNodes && sigma * rhoOf(nodes) <= kMaxClosureOpticalRadius) ++nodes;
  if (nodes == 0) return std::nullopt;
  const int tasks = nodes * s.sunDirections;
  std::vector<Tally> tallies(tasks);
  std::atomic<int> done{0};
  tbb::parallel_for(0, tasks, [&](int task) {
    const int node = task / s.sunDirections;
    const float rho = rhoOf(node);
    const glm::dvec3 l = fibonacciDirection(task % s.sunDirections, s.sunDirections);
    Tally& t = tallies[task];
    t.power.assign(s.muBins, 0.0);
    t.power2.assign(s.muBins, 0.0);
    t.model.assign(s.muBins, 0.0);
    tracePhotons(t, particle, sigma * rho, l, first, later, s.photonsPerDirection, maxOrder, s.seed,
                 static_cast<std::uint64_t>(task), s.muBins);
    integrateModel(t, od, outerThird, multiple, rho, l, g, s);
    reportProgress(progress, "angular closure", static_cast<double>(++done) / tasks);
  });
  AngularClosure c;
  c.values.clear();
  c.log2RhoFirst = s.log2RhoFirst;
  c.log2RhoStep = s.log2RhoStep;
  c.densityNodes = nodes;
  c.muBins = s.muBins;
  c.ownCoreShadow = s.ownCoreShadow;
  c.ownCoreShadowMax = s.ownCoreShadowMax;
  for (int node = 0; node < nodes; ++node)
    for (int b = 0; b < s.muBins; ++b) {
      // sums in task order: the same whatever the thread count
      double power = 0.0, power2 = 0.0, model = 0.0;
      for (int k = 0; k < s.sunDirections; ++k) {
        const Tally& t = tallies[node * s.sunDirections + k];
        power += t.power[b];
        power2 += t.power2[b];
        model += t.model[b];
      }
      const double photons = static_cast<double>(s.photonsPerDirection) * s.sunDirections;
      const double mean = power / s.sunDirections;
      // standard error of the bin's power: per-photon tallies w·[in bin] over all photons
      const double perPhoton = power / photons, perPhoton2 = power2 / photons;
      const double se = std::sqrt(std::max(0.0, perPhoton2 - perPhoton * perPhoton) / photons) * photons / s.sunDirections;
      const bool usable = model > 1e-9 && mean > 0.0;
      c.values.push_back(usable ? static_cast<float>(mean / (model / s.sunDirections)) : 1.0f);
      c.relativeErrors.push_back(usable ? static_cast<float>(se / mean) : 0.0f);
    }
  return c;
}

void attachAngularClosure(Table4D& multiple, const Table4D& od, const ReferenceParticle& particle, const Phase& first,
                          const Phase& later, const AngularClosureSettings& settings, const ProgressFn& progress) {
  if (const auto closure = computeAngularClosure(od, multiple, particle, first, later, settings, progress))
    multiple.parameters()["angular_closure"] = angularClosureToJson(*closure);
}

}  // namespace cloudlut::bake
