#include "bake/ChordMatterProfile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "core/Defaults.h"

namespace cloudlut::bake {

namespace {

constexpr int kDirections = 16;
constexpr int kAcross = 24;     // chords per side of the grid over the disc
constexpr int kPerDiameter = 256;

// The matter of one direction's chords: (outer thirds, all), summed in a fixed order.
std::array<double, 2> directionMatter(const ReferenceParticle& particle, int index) {
  // Fibonacci sphere direction `index` of kDirections, and two axes across it
  const double golden = 2.39996322972865332;  // π(3 − √5), rad
  const double z = 1.0 - (index + 0.5) * 2.0 / kDirections;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const glm::dvec3 v(r * std::cos(golden * index), r * std::sin(golden * index), z);
  const glm::dvec3 a = glm::normalize(glm::cross(v, std::abs(v.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 b = glm::cross(v, a);
  const double threshold = defaults::kFirstMatterThreshold;
  std::vector<double> samples;
  double outer = 0.0, all = 0.0;
  for (int j = 0; j < kAcross; ++j)
    for (int i = 0; i < kAcross; ++i) {
      const double x = -1.0 + (i + 0.5) * 2.0 / kAcross, y = -1.0 + (j + 0.5) * 2.0 / kAcross;
      const double half = std::sqrt(std::max(0.0, 1.0 - x * x - y * y));
      const int n = static_cast<int>(std::ceil(kPerDiameter * half));
      if (n < 1) continue;
      const double dt = 2.0 * half / n;
      samples.assign(static_cast<std::size_t>(n), 0.0);
      int first = -1, last = -1;
      for (int k = 0; k < n; ++k) {
        const glm::dvec3 p = x * a + y * b + (-half + (k + 0.5) * dt) * v;
        const double d = particle.density(glm::vec3(p));
        samples[static_cast<std::size_t>(k)] = d;
        if (d >= threshold) {
          if (first < 0) first = k;
          last = k;
        }
      }
      if (first < 0) continue;
      // the span [first, last + 1) in samples, cut in thirds at fractional sample positions
      const double from = first, span = last + 1 - first;
      for (int k = first; k <= last; ++k) {
        // the sample's cell [k, k + 1) split between the thirds it straddles
        const double lo = (k - from) / span, hi = (k + 1 - from) / span;
        const double middle = std::max(0.0, std::min(hi, 2.0 / 3.0) - std::max(lo, 1.0 / 3.0));
        const double d = samples[static_cast<std::size_t>(k)] * dt;
        all += d;
        outer += d * (1.0 - middle / (hi - lo));
      }
    }
  return {outer, all};
}

}  // namespace

double measureChordOuterThird(const ReferenceParticle& particle) {
  std::array<std::array<double, 2>, kDirections> parts{};
  tbb::parallel_for(0, kDirections, [&](int d) { parts[static_cast<std::size_t>(d)] = directionMatter(particle, d); });
  double outer = 0.0, all = 0.0;
  for (const auto& p : parts) {
    outer += p[0];
    all += p[1];
  }
  return all > 0.0 ? 0.5 * outer / all : 1.0 / 3.0;
}

}  // namespace cloudlut::bake
