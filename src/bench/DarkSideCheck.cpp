#include "bench/DarkSideCheck.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/TableLookup.h"

namespace cloudlut::bench {

DarkSideComparison compareDarkSide(const Table4D& single, const Table4D& multiple, double rho,
                                   const std::vector<reference::ExitBin>& bins, long long photons,
                                   std::uint64_t seed) {
  const double sigma = static_cast<double>(unitOpticalRadius(multiple)) * rho;
  const auto t0 = std::chrono::steady_clock::now();
  const auto tally =
      reference::tallyExitRadiance(sigma, defaults::kFirstPhase, defaults::kLaterPhase, bins, photons, seed);
  DarkSideComparison out;
  out.tallySeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const glm::vec3 l(0, 0, 1);
  const auto L = [&](const glm::dvec3& Sd, const glm::dvec3& vd) {
    const glm::vec3 S(Sd), v(vd);
    const float r = static_cast<float>(rho);
    const double p1 = phaseValue(defaults::kFirstPhase, glm::dot(v, l));
    return p1 * lookupScattering(single, S, v, l, r) + lookupScattering(multiple, S, v, l, r);
  };
  std::vector<double> abs;
  for (std::size_t k = 0; k < bins.size(); ++k) {
    DarkSideBinResult b;
    b.table = reference::binMean(bins[k], 6, L);
    b.photons = tally[k].radiance;
    b.se = tally[k].se;
    out.bins.push_back(b);
    const double e = b.relativeError();
    abs.push_back(std::abs(e));
    if (std::abs(e) > std::abs(out.worstError)) {
      out.worstError = e;
      out.worstSe = b.photons > 0 ? b.se / b.photons : 0.0;
    }
  }
  if (!abs.empty()) {
    std::sort(abs.begin(), abs.end());
    const std::size_t n = abs.size();
    out.medianAbsError = n % 2 ? abs[n / 2] : 0.5 * (abs[n / 2 - 1] + abs[n / 2]);
  }
  return out;
}

}  // namespace cloudlut::bench
