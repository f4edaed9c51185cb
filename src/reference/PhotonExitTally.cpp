#include "reference/PhotonExitTally.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "reference/SphereMonteCarlo.h"

namespace cloudlut::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

struct Angles {
  double thetaS, thetaV, phiV;
};

// The tables' angles of the exit sample S = P, v = −ω (header).
Angles anglesOf(const glm::dvec3& P, const glm::dvec3& omega) {
  const glm::dvec3 l(0, 0, 1), S = glm::normalize(P), v = -omega;
  Angles a;
  a.thetaS = std::acos(std::clamp(S.z, -1.0, 1.0));
  a.thetaV = std::acos(std::clamp(-glm::dot(v, S), -1.0, 1.0));
  const glm::dvec3 c = glm::cross(l, S);
  const double len = glm::length(c);
  const glm::dvec3 fy = len > 1e-12 ? c / len : glm::dvec3(0, 1, 0);
  const glm::dvec3 fx = glm::cross(fy, S);
  a.phiV = std::abs(std::atan2(glm::dot(v, fy), glm::dot(v, fx)));
  return a;
}

bool inside(const ExitBin& b, const Angles& a) {
  return a.thetaS >= b.thetaS[0] && a.thetaS < b.thetaS[1] && a.thetaV >= b.thetaV[0] && a.thetaV < b.thetaV[1] &&
         a.phiV >= b.phiV[0] && a.phiV <= b.phiV[1];
}

double measureOf(const ExitBin& b) {
  const double area = 2.0 * kPi * (std::cos(b.thetaS[0]) - std::cos(b.thetaS[1]));
  const double s0 = std::sin(b.thetaV[0]), s1 = std::sin(b.thetaV[1]);
  return area * (b.phiV[1] - b.phiV[0]) * (s1 * s1 - s0 * s0);
}

}  // namespace

std::vector<ExitBinRadiance> tallyExitRadiance(double sigma, const Phase& first, const Phase& later,
                                               const std::vector<ExitBin>& bins, long long photons,
                                               std::uint64_t seed) {
  if (photons < 1) throw std::invalid_argument("tallyExitRadiance: photons must be positive");
  const std::size_t nb = bins.size();
  const long long blocks = (photons + kPathsPerBlock - 1) / kPathsPerBlock;
  // Per block: Σw, Σw² and hits of every bin.
  std::vector<double> sw(static_cast<std::size_t>(blocks) * nb, 0.0), sw2(sw.size(), 0.0);
  std::vector<long long> hits(sw.size(), 0);
  tbb::parallel_for(0LL, blocks, [&](long long b) {
    McRng rng(seed, 0xe817ULL, static_cast<std::uint64_t>(b));
    const long long count = std::min(kPathsPerBlock, photons - b * kPathsPerBlock);
    const std::size_t base = static_cast<std::size_t>(b) * nb;
    for (long long i = 0; i < count; ++i) {
      const ForwardPhoton p = traceForwardPhoton(sigma, first, later, rng);
      const Angles a = anglesOf(p.exitPoint, p.exitDirection);
      for (std::size_t k = 0; k < nb; ++k) {
        if (!inside(bins[k], a)) continue;
        sw[base + k] += p.weight;
        sw2[base + k] += p.weight * p.weight;
        ++hits[base + k];
      }
    }
  });
  std::vector<ExitBinRadiance> out(nb);
  const double n = static_cast<double>(photons);
  for (std::size_t k = 0; k < nb; ++k) {
    double s = 0.0, s2 = 0.0;
    long long h = 0;
    for (long long b = 0; b < blocks; ++b) {
      const std::size_t i = static_cast<std::size_t>(b) * nb + k;
      s += sw[i];
      s2 += sw2[i];
      h += hits[i];
    }
    const double scale = kPi / measureOf(bins[k]);
    const double mean = s / n;
    const double var = std::max(0.0, s2 / n - mean * mean);
    out[k].radiance = scale * mean;
    out[k].se = scale * std::sqrt(var / n);
    out[k].hits = h;
  }
  return out;
}

double binMean(const ExitBin& bin, int n, const std::function<double(const glm::dvec3& S, const glm::dvec3& v)>& L) {
  const double c0 = std::cos(bin.thetaS[0]), c1 = std::cos(bin.thetaS[1]);
  const double q0 = std::pow(std::sin(bin.thetaV[0]), 2), q1 = std::pow(std::sin(bin.thetaV[1]), 2);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double cS = c0 + (c1 - c0) * (i + 0.5) / n, sS = std::sqrt(std::max(0.0, 1.0 - cS * cS));
    const glm::dvec3 S(sS, 0.0, cS), fx(cS, 0.0, -sS), fy(0.0, 1.0, 0.0);
    for (int j = 0; j < n; ++j) {
      const double q = q0 + (q1 - q0) * (j + 0.5) / n;
      const double sV = std::sqrt(q), cV = std::sqrt(std::max(0.0, 1.0 - q));
      for (int k = 0; k < n; ++k) {
        const double ph = bin.phiV[0] + (bin.phiV[1] - bin.phiV[0]) * (k + 0.5) / n;
        const glm::dvec3 v = sV * (std::cos(ph) * fx + std::sin(ph) * fy) - cV * S;
        sum += L(S, v);
      }
    }
  }
  return sum / (static_cast<double>(n) * n * n);
}

std::vector<ExitBin> darkSideBins(int nS, int nV, int nP) {
  nS = std::max(nS, 1);
  nV = std::max(nV, 1);
  nP = std::max(nP, 1);
  const auto edge = [](double a, double b, int i, int n) { return (a + (b - a) * i / n) * kDeg; };
  std::vector<ExitBin> bins;
  for (int i = 0; i < nS; ++i)
    for (int j = 0; j < nV; ++j)
      for (int k = 0; k < nP; ++k)
        bins.push_back({{edge(100, 180, i, nS), edge(100, 180, i + 1, nS)},
                        {edge(0, 90, j, nV), edge(0, 90, j + 1, nV)},
                        {edge(0, 180, k, nP), edge(0, 180, k + 1, nP)}});
  return bins;
}

}  // namespace cloudlut::reference
