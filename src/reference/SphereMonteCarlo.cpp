#include "reference/SphereMonteCarlo.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "core/Glsl.h"

namespace cloudlut::reference {

namespace {

constexpr double kPi = 3.14159265358979323846;

double phaseAt(const Phase& p, double mu) {
  return static_cast<double>(cloudlut::phaseValue(p, static_cast<float>(mu)));
}

// Distance from x (|x| ≤ 1) along the unit direction d to the unit sphere.
double distanceToBoundary(const glm::dvec3& x, const glm::dvec3& d) {
  const double b = glm::dot(x, d);
  const double c = glm::dot(x, x) - 1.0;
  const double disc = std::max(b * b - c, 0.0);
  return std::max(-b + std::sqrt(disc), 0.0);
}

struct PathSums {
  double s[3] = {0, 0, 0};   // single, multipleN, multipleAll
  double s2[3] = {0, 0, 0};  // sums of squares
  double vertices = 0;
};

// One backward path from S along v; adds its per-order tallies to `sums`.
//
// Order k+1 is estimated at vertex k by two techniques combined with the balance heuristic:
//   A: the path's own continuation (direction d' drawn from PM about d), then next-event
//      estimation at the next vertex with P1(l·d');
//   B: a direction drawn from P1 about l (the sun's forward peak), a forced free flight along
//      it and next-event estimation there, weighted by PM(d·d'').
// Their direction pdfs are PM(d·ω) and P1(l·ω); weights pdf / (pdfA + pdfB). Sharp P1 peaks
// (g = 0.9, Jendersie–d'Eon) are thereby sampled instead of hit by chance.
void tracePath(const SphereMcQuery& q, const glm::dvec3& S, const glm::dvec3& v,
               const glm::dvec3& l, const SphereMcSettings& st, McRng& rng, PathSums& sums) {
  const double sigma = q.sigma;
  glm::dvec3 x = S, d = v;
  double w = 1.0, misA = 1.0;
  double tally[3] = {0, 0, 0};
  long long vertices = 0;
  const auto add = [&](int order, double c) {
    if (order == 1) tally[0] += c;
    else {
      if (order <= st.splitOrder) tally[1] += c;
      tally[2] += c;
    }
  };
  // Forced free flight from p along dir: returns the collision point, multiplies the weight.
  const auto fly = [&](const glm::dvec3& p, const glm::dvec3& dir, double chord, double& weight) {
    const double pInt = -std::expm1(-sigma * chord);
    weight *= pInt;
    if (!(pInt > 0.0)) return p;
    const double t = std::min(-std::log1p(-rng.next() * pInt) / sigma, chord);
    glm::dvec3 y = p + t * dir;
    const double r2 = glm::dot(y, y);
    if (r2 > 1.0) y /= std::sqrt(r2);
    return y;
  };
  const int lastVertex = st.maxOrder > 0 ? st.maxOrder : 10000000;
  for (int k = 1; k <= lastVertex; ++k) {
    const double chord = k == 1 ? std::max(-2.0 * glm::dot(S, v), 0.0) : distanceToBoundary(x, d);
    x = fly(x, d, chord, w);
    if (!(w > 0.0)) break;
    ++vertices;
    // Next-event estimation: sunlight scattered for the first time here, toward -d.
    add(k, misA * w * phaseAt(st.first, glm::dot(l, d)) * std::exp(-sigma * distanceToBoundary(x, l)));
    // Technique B for order k + 1.
    if (k < lastVertex) {
      const glm::dvec3 dB = sampleScatteredDirection(l, st.first, rng);
      const double pmB = phaseAt(st.later, glm::dot(d, dB));
      const double p1B = phaseAt(st.first, glm::dot(l, dB));
      double wB = w;
      const glm::dvec3 xB = fly(x, dB, distanceToBoundary(x, dB), wB);
      if (wB > 0.0 && pmB + p1B > 0.0)
        add(k + 1, wB * pmB * std::exp(-sigma * distanceToBoundary(xB, l)) * p1B / (pmB + p1B));
    }
    // Russian roulette.
    if (w < st.rouletteWeight) {
      const double survive = w / st.rouletteWeight;
      if (rng.next() >= survive) break;
      w = st.rouletteWeight;
    }
    // Technique A: continue backward; the light arriving here came from direction d' with
    // cos(d, d') drawn exactly from the later phase function.
    const glm::dvec3 dn = sampleScatteredDirection(d, st.later, rng);
    const double pmA = phaseAt(st.later, glm::dot(d, dn));
    const double p1A = phaseAt(st.first, glm::dot(l, dn));
    misA = pmA + p1A > 0.0 ? pmA / (pmA + p1A) : 1.0;
    d = dn;
  }
  for (int i = 0; i < 3; ++i) {
    sums.s[i] += tally[i];
    sums.s2[i] += tally[i] * tally[i];
  }
  sums.vertices += static_cast<double>(vertices);
}

}  // namespace


double unscatteredShare(double sigma) {
  if (sigma < 1e-4) return 1.0 - 4.0 * sigma / 3.0;  // series: 1 − (4/3)σ + σ² …
  return (1.0 - std::exp(-2.0 * sigma) * (1.0 + 2.0 * sigma)) / (2.0 * sigma * sigma);
}

std::vector<SphereMcEstimate> estimateSphereRadiance(const std::vector<SphereMcQuery>& queries,
                                                     const SphereMcSettings& settings,
                                                     const ProgressFn& progress) {
  if (settings.paths < 2) throw std::invalid_argument("at least 2 paths per query are needed");
  const long long blocks = (settings.paths + kPathsPerBlock - 1) / kPathsPerBlock;
  const std::size_t rows = queries.size();
  const std::size_t items = rows * static_cast<std::size_t>(blocks);
  std::vector<PathSums> partial(items);
  std::atomic<std::size_t> done{0};
  tbb::parallel_for(std::size_t(0), items, [&](std::size_t item) {
    const std::size_t row = item / static_cast<std::size_t>(blocks);
    const long long block = static_cast<long long>(item % static_cast<std::size_t>(blocks));
    const SphereMcQuery& q = queries[row];
    const glm::dvec3 S = glm::normalize(q.S), v = glm::normalize(q.v), l = glm::normalize(q.l);
    McRng rng(settings.seed, row, static_cast<std::uint64_t>(block));
    const long long first = block * kPathsPerBlock;
    const long long count = std::min(kPathsPerBlock, settings.paths - first);
    PathSums sums;
    if (glm::dot(S, v) < 0.0 && q.sigma > 0.0)
      for (long long i = 0; i < count; ++i) tracePath(q, S, v, l, settings, rng, sums);
    partial[item] = sums;
    const std::size_t n = ++done;
    if (progress && (n % 16 == 0 || n == items))
      reportProgress(progress, "reference", static_cast<double>(n) / static_cast<double>(items));
  });
  std::vector<SphereMcEstimate> out(rows);
  const double N = static_cast<double>(settings.paths);
  for (std::size_t r = 0; r < rows; ++r) {
    PathSums total;
    for (long long b = 0; b < blocks; ++b) {
      const PathSums& p = partial[r * static_cast<std::size_t>(blocks) + static_cast<std::size_t>(b)];
      for (int i = 0; i < 3; ++i) {
        total.s[i] += p.s[i];
        total.s2[i] += p.s2[i];
      }
      total.vertices += p.vertices;
    }
    double mean[3], se[3];
    for (int i = 0; i < 3; ++i) {
      mean[i] = total.s[i] / N;
      const double var = std::max(0.0, (total.s2[i] / N - mean[i] * mean[i]) * N / (N - 1.0));
      se[i] = std::sqrt(var / N);
    }
    out[r] = {mean[0], se[0], mean[1], se[1], mean[2], se[2], total.vertices / N};
  }
  return out;
}

ForwardPhoton traceForwardPhoton(double sigma, const Phase& first, const Phase& later, McRng& rng) {
  const glm::dvec3 l(0, 0, 1);
  // Uniform point on the unit disk facing the sun, entering along -l.
  const double rr = std::sqrt(rng.next()), ph = 2.0 * kPi * rng.next();
  const double px = rr * std::cos(ph), py = rr * std::sin(ph);
  const double h = std::sqrt(std::max(0.0, 1.0 - rr * rr));
  glm::dvec3 x(px, py, h), d = -l;
  const double chord = 2.0 * h;
  const double pInt = -std::expm1(-sigma * chord);
  ForwardPhoton out;
  out.unscatteredWeight = 1.0 - pInt;
  out.weight = pInt;  // forced first collision
  x += (std::min(-std::log1p(-rng.next() * pInt) / sigma, chord)) * d;
  d = sampleScatteredDirection(d, first, rng);
  int k = 1;
  for (;;) {
    const double dist = distanceToBoundary(x, d);
    const double t = -std::log(1.0 - rng.next()) / sigma;
    if (t >= dist) {
      x += dist * d;
      break;
    }
    x += t * d;
    ++k;
    d = sampleScatteredDirection(d, later, rng);
    if (k > 50000000) break;
  }
  out.order = k;
  out.exitPoint = glm::normalize(x);
  out.exitDirection = d;
  return out;
}

PhotonShares photonTraceSphere(double sigma, const Phase& first, const Phase& later,
                               long long photons, std::uint64_t seed, int maxOrder) {
  if (photons < 1 || maxOrder < 1) throw std::invalid_argument("photonTraceSphere: bad counts");
  const long long blocks = (photons + kPathsPerBlock - 1) / kPathsPerBlock;
  struct Block {
    std::vector<double> byOrder;
    double beyond = 0, unscattered = 0;
  };
  std::vector<Block> partial(static_cast<std::size_t>(blocks));
  tbb::parallel_for(0LL, blocks, [&](long long b) {
    Block blk;
    blk.byOrder.assign(static_cast<std::size_t>(maxOrder) + 1, 0.0);
    McRng rng(seed, 0xf0f0f0f0ULL, static_cast<std::uint64_t>(b));
    const long long count = std::min(kPathsPerBlock, photons - b * kPathsPerBlock);
    for (long long i = 0; i < count; ++i) {
      const ForwardPhoton p = traceForwardPhoton(sigma, first, later, rng);
      blk.unscattered += p.unscatteredWeight;
      if (p.order <= maxOrder) blk.byOrder[static_cast<std::size_t>(p.order)] += p.weight;
      else blk.beyond += p.weight;
    }
    partial[static_cast<std::size_t>(b)] = std::move(blk);
  });
  PhotonShares out;
  out.byOrder.assign(static_cast<std::size_t>(maxOrder) + 1, 0.0);
  for (const Block& b : partial) {
    out.unscattered += b.unscattered;
    out.beyond += b.beyond;
    for (std::size_t k = 0; k < b.byOrder.size(); ++k) out.byOrder[k] += b.byOrder[k];
  }
  const double n = static_cast<double>(photons);
  out.unscattered /= n;
  out.beyond /= n;
  out.total = out.unscattered + out.beyond;
  for (double& s : out.byOrder) {
    s /= n;
    out.total += s;
  }
  out.standardError = 0.5 / std::sqrt(n);
  return out;
}

BackwardShares integrateBackwardShares(double sigma, const SphereMcSettings& settings,
                                       long long samples) {
  // Each sample: S uniform on the sphere, v cosine-weighted about -S, l = +z, one path.
  const long long blocks = (samples + kPathsPerBlock - 1) / kPathsPerBlock;
  std::vector<PathSums> partial(static_cast<std::size_t>(blocks));
  const glm::dvec3 l(0, 0, 1);
  tbb::parallel_for(0LL, blocks, [&](long long b) {
    McRng rng(settings.seed, 0xbacdULL, static_cast<std::uint64_t>(b));
    PathSums sums;
    const long long count = std::min(kPathsPerBlock, samples - b * kPathsPerBlock);
    for (long long i = 0; i < count; ++i) {
      const double z = 1.0 - 2.0 * rng.next(), ph = 2.0 * kPi * rng.next();
      const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
      const glm::dvec3 S(s * std::cos(ph), s * std::sin(ph), z);
      const double cosT = std::sqrt(std::max(rng.next(), 1e-300));  // cosine-weighted
      const glm::dvec3 v = rotateAbout(-S, cosT, rng.next());
      SphereMcQuery q{S, v, l, sigma};
      tracePath(q, S, v, l, settings, rng, sums);
    }
    partial[static_cast<std::size_t>(b)] = sums;
  });
  PathSums total;
  for (const PathSums& p : partial)
    for (int i = 0; i < 3; ++i) {
      total.s[i] += p.s[i];
      total.s2[i] += p.s2[i];
    }
  const double N = static_cast<double>(samples), scale = 4.0 * kPi;
  double mean[3], se[3];
  for (int i = 0; i < 3; ++i) {
    mean[i] = total.s[i] / N;
    se[i] = std::sqrt(std::max(0.0, total.s2[i] / N - mean[i] * mean[i]) / N);
  }
  return {scale * mean[0], scale * se[0], scale * mean[1], scale * se[1], scale * mean[2], scale * se[2]};
}

}  // namespace cloudlut::reference
