#include "reference/ScenePathTracer.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "core/DetailNoise.h"
#include "core/Glsl.h"
#include "reference/ParticleBvh.h"

namespace cloudlut::reference {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The part of a ray inside one particle: [t0, t1] in world units along the ray, the particle's
// majorant along the ray, and the ray in the particle's unit-sphere coordinates.
struct Span {
  double t0, t1;
  double majorant;  // β·R·ρ·|M⁻¹ω|  (ρ̂ ≤ 1)
  glm::dvec3 o, d;  // unit-sphere origin and (unnormalised) direction: p(t) = o + t·d
};

// Per-thread scratch: the spans active on a piece, the BVH's candidate particles, and the BVH
// (null: test every particle).
struct Scratch {
  std::vector<const Span*> active;
  std::vector<std::uint32_t> candidates;
  const ParticleBvh* bvh = nullptr;
};

// The ray against the particles: the BVH's candidates in index order (or every particle), then
// the exact ellipsoid. Both paths test the same particles that can be hit, in the same order, so
// the spans (and every sum over them) are the same bit for bit.
class RaySpans {
 public:
  RaySpans(const SceneMedium& m, const glm::dvec3& origin, const glm::dvec3& dir, Scratch& scratch, double tMax = kInf)
      : rayOrigin(origin), rayDir(dir), detailBound(1.0 + static_cast<double>(m.detail.x)) {
    if (scratch.bvh) {
      scratch.bvh->candidates(origin, dir, tMax, scratch.candidates);
      for (const std::uint32_t i : scratch.candidates) addParticle(m, m.particles[i], origin, dir, tMax);
    } else {
      for (const SceneParticle& p : m.particles) addParticle(m, p, origin, dir, tMax);
    }
    // Piece boundaries.
    bounds.reserve(2 * spans.size());
    for (const Span& s : spans) {
      bounds.push_back(s.t0);
      bounds.push_back(s.t1);
    }
    std::sort(bounds.begin(), bounds.end());
    bounds.erase(std::unique(bounds.begin(), bounds.end()), bounds.end());
  }

  // The exact ellipsoid test of one particle: the span of the ray inside it, if any.
  void addParticle(const SceneMedium& m, const SceneParticle& p, const glm::dvec3& origin, const glm::dvec3& dir,
                   double tMax) {
    {
      const glm::dvec3 o = p.toParticle * (origin - p.center), d = p.toParticle * dir;
      const double a = glm::dot(d, d), b = glm::dot(o, d), c = glm::dot(o, o) - 1.0;
      const double disc = b * b - a * c;
      if (disc <= 0.0 || a <= 0.0) return;
      const double sq = std::sqrt(disc);
      // Stable roots of a t² + 2 b t + c = 0.
      const double q = b >= 0 ? -(b + sq) : -(b - sq);
      double r0 = q / a, r1 = c / q;
      if (q == 0.0) r0 = r1 = -b / a;
      if (r0 > r1) std::swap(r0, r1);
      const double t0 = std::max(r0, 0.0), t1 = std::min(r1, tMax);
      if (!(t1 > t0)) return;
      spans.push_back({t0, t1, m.unitOpticalRadius * p.density * std::sqrt(a) * detailBound, o, d});
    }
  }

  std::vector<Span> spans;
  std::vector<double> bounds;
  glm::dvec3 rayOrigin, rayDir;  // the world ray: x(t) = rayOrigin + t·rayDir
  double detailBound;      // 1 + a: the largest detail factor, folded into every majorant

  bool empty() const { return spans.empty(); }

  // Majorant on the piece containing t, and the spans active there.
  double majorantAt(double tMid, std::vector<const Span*>& active) const {
    active.clear();
    double maj = 0;
    for (const Span& s : spans)
      if (s.t0 <= tMid && tMid <= s.t1) {
        active.push_back(&s);
        maj += s.majorant;
      }
    return maj;
  }
};

// σ(x(t)) = m(x) · Σ_i σ_i(x): the spans' majorants carry the bound 1 + a of the detail factor m,
// so the factor enters as m / (1 + a) (exactly 1 without detail).
double extinctionAt(const SceneMedium& m, const RaySpans& r, const std::vector<const Span*>& active, double t) {
  double sigma = 0;
  for (const Span* s : active) {
    const glm::dvec3 p = s->o + t * s->d;
    sigma += s->majorant * static_cast<double>(m.model->density(glm::vec3(p)));
  }
  if (m.detail.x > 0.0f && sigma > 0.0)
    sigma *= static_cast<double>(glsl::detailDensityFactor(glm::vec3(r.rayOrigin + t * r.rayDir), m.detail)) / r.detailBound;
  return sigma;
}

double expSample(McRng& rng) { return -std::log(1.0 - rng.next()); }

// Delta tracking: distance to the next real collision, or +inf when the ray leaves the medium.
double freeFlight(const SceneMedium& m, const RaySpans& r, McRng& rng, std::vector<const Span*>& active) {
  for (std::size_t k = 0; k + 1 < r.bounds.size(); ++k) {
    const double ta = r.bounds[k], tb = r.bounds[k + 1];
    const double maj = r.majorantAt(0.5 * (ta + tb), active);
    if (!(maj > 0)) continue;
    double t = ta;
    for (;;) {
      t += expSample(rng) / maj;
      if (t >= tb) break;
      const double sigma = extinctionAt(m, r, active, t);
      if (rng.next() * maj < sigma) return t;
    }
  }
  return kInf;
}

// Transmittance along the whole ray: exact for homogeneous particles, ratio tracking otherwise.
double transmittance(const SceneMedium& m, const RaySpans& r, McRng& rng, std::vector<const Span*>& active) {
  if (m.model->model() == DensityModel::Sphere && !(m.detail.x > 0.0f)) {
    double tau = 0;
    for (const auto& s : r.spans) tau += s.majorant * (s.t1 - s.t0);
    return std::exp(-tau);
  }
  double T = 1;
  for (std::size_t k = 0; k + 1 < r.bounds.size(); ++k) {
    const double ta = r.bounds[k], tb = r.bounds[k + 1];
    const double maj = r.majorantAt(0.5 * (ta + tb), active);
    if (!(maj > 0)) continue;
    double t = ta;
    for (;;) {
      t += expSample(rng) / maj;
      if (t >= tb) break;
      T *= 1.0 - extinctionAt(m, r, active, t) / maj;
    }
    if (T <= 0) return 0;
  }
  return T;
}

// A unit vector at angle acos(mu) from `axis`, uniformly around it.
glm::dvec3 rotateAround(const glm::dvec3& axis, double mu, double phi) {
  const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 x = glm::normalize(glm::cross(helper, axis)), y = glm::cross(axis, x);
  const double s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  return glm::normalize(mu * axis + s * (std::cos(phi) * x + std::sin(phi) * y));
}

double phaseAt(const Phase& p, double mu) {
  return static_cast<double>(cloudlut::phaseValue(p, static_cast<float>(mu)));
}

struct PathSample {
  double single = 0, multiple = 0, sky = 0, transmittance = 1;
  int vertices = 0;
  bool truncated = false;  // cut at kMaxPathVertices
};

PathSample tracePath(const SceneMedium& m, const SceneLight& light, const ScenePtSettings& st, glm::dvec3 origin,
                     glm::dvec3 dir, McRng& rng, Scratch& sc) {
  std::vector<const Span*>& active = sc.active;
  PathSample out;
  {
    const RaySpans primary(m, origin, dir, sc);
    if (primary.empty()) return out;
    out.transmittance = transmittance(m, primary, rng, active);
    const double t = freeFlight(m, primary, rng, active);
    if (t == kInf) return out;
    origin += t * dir;
  }
  const glm::dvec3 l = light.sunDirection;
  const int maxOrder = st.maxOrder > 0 ? st.maxOrder : kMaxPathVertices;
  for (int order = 1;; ++order) {
    out.vertices = order;
    // Next-event estimation: sunlight's first scattering at this vertex.
    const RaySpans toSun(m, origin, l, sc);
    const double sun = phaseAt(st.first, glm::dot(dir, l)) * transmittance(m, toSun, rng, active);
    (order == 1 ? out.single : out.multiple) += sun;
    if (order >= maxOrder) {
      out.truncated = st.maxOrder <= 0;
      break;
    }
    // Continue along a direction sampled from the later phase function.
    const double mu = samplePhaseCosine(st.later, rng);
    dir = rotateAround(dir, mu, 2.0 * 3.14159265358979323846 * rng.next());
    const RaySpans next(m, origin, dir, sc);
    const double t = freeFlight(m, next, rng, active);
    if (t == kInf) {
      out.sky += dir.y >= 0.0 ? 1.0 : light.skyBelow;  // the sky (above the horizon) or the ground's return
      break;
    }
    origin += t * dir;
  }
  return out;
}

struct Moments {
  double n = 0;
  double s = 0, s2 = 0, mu = 0, mu2 = 0, k = 0, k2 = 0, T = 0, T2 = 0, sun2 = 0, sunK = 0, v = 0;
  void add(const PathSample& p) {
    n += 1;
    s += p.single;
    s2 += p.single * p.single;
    mu += p.multiple;
    mu2 += p.multiple * p.multiple;
    k += p.sky;
    k2 += p.sky * p.sky;
    T += p.transmittance;
    T2 += p.transmittance * p.transmittance;
    const double sun = p.single + p.multiple;
    sun2 += sun * sun;
    sunK += sun * p.sky;
    v += p.vertices;
  }
  // Standard error of a mean from the sums.
  double se(double sum, double sum2) const {
    if (n < 2) return 0;
    const double var = std::max(0.0, (sum2 - sum * sum / n) / (n - 1));
    return std::sqrt(var / n);
  }
  RayEstimate estimate() const {
    RayEstimate e;
    e.single = s / n;
    e.singleSe = se(s, s2);
    e.multiple = mu / n;
    e.multipleSe = se(mu, mu2);
    e.sky = k / n;
    e.skySe = se(k, k2);
    e.transmittance = T / n;
    e.transmittanceSe = se(T, T2);
    e.sunSe = se(s + mu, sun2);
    e.sunSkyCov = n >= 2 ? (sunK - (s + mu) * k / n) / (n - 1) / n : 0.0;
    e.vertices = v / n;
    return e;
  }
};

}  // namespace

double homogeneousOpticalDepth(const SceneMedium& medium, const glm::dvec3& origin, const glm::dvec3& direction,
                               double t0, double t1) {
  Scratch sc;
  const RaySpans r(medium, origin + t0 * direction, direction, sc, t1 - t0);
  double tau = 0;
  for (const auto& s : r.spans) tau += s.majorant / r.detailBound * (s.t1 - s.t0);
  return tau;
}

RayEstimate estimateRay(const SceneMedium& medium, const SceneLight& light, const ScenePtSettings& settings,
                        const glm::dvec3& origin, const glm::dvec3& direction, long long samples,
                        std::uint64_t stream) {
  McRng rng(settings.seed, stream, 0);
  std::optional<ParticleBvh> bvh;
  Scratch sc;
  if (!settings.bruteForce && medium.particles.size() >= kBvhMinParticles) sc.bvh = &bvh.emplace(medium.particles);
  Moments mo;
  const glm::dvec3 d = glm::normalize(direction);
  for (long long i = 0; i < samples; ++i) mo.add(tracePath(medium, light, settings, origin, d, rng, sc));
  return mo.estimate();
}

ScenePtImage renderScene(const SceneMedium& medium, const SceneLight& light, const ScenePtSettings& settings,
                         int width, int height, const CameraRayFn& cameraRay, const ProgressFn& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  ScenePtImage img;
  img.width = width;
  img.height = height;
  img.pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  constexpr int kTile = 16;
  const int tilesX = (width + kTile - 1) / kTile, tilesY = (height + kTile - 1) / kTile;
  const int tiles = tilesX * tilesY;
  std::atomic<int> done{0};
  reportProgress(progress, "path tracing", 0.0);
  std::atomic<long long> truncated{0}, pixelsDone{0};
  const auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
  const double pixelCount = static_cast<double>(img.pixels.size());
  std::optional<ParticleBvh> bvh;
  if (!settings.bruteForce && medium.particles.size() >= kBvhMinParticles) bvh.emplace(medium.particles);
  tbb::parallel_for(0, tiles, [&](int tile) {
    Scratch sc;
    sc.bvh = bvh ? &*bvh : nullptr;
    const int tx = tile % tilesX, ty = tile / tilesX;
    for (int y = ty * kTile; y < std::min(height, (ty + 1) * kTile); ++y)
      for (int x = tx * kTile; x < std::min(width, (tx + 1) * kTile); ++x) {
        const std::size_t index = static_cast<std::size_t>(y) * width + x;
        McRng rng(settings.seed, index, 0);
        Moments mo;
        glm::dvec3 o, d;
        if (!settings.jitter) cameraRay(x + 0.5, y + 0.5, o, d);
        for (int s = 0; s < settings.samplesPerPixel; ++s) {
          if (settings.jitter) {
            const double jx = rng.next(), jy = rng.next();
            cameraRay(x + jx, y + jy, o, d);
          }
          const PathSample path = tracePath(medium, light, settings, o, glm::normalize(d), rng, sc);
          if (path.truncated) ++truncated;
          mo.add(path);
        }
        img.pixels[index] = mo.estimate();
        const long long finished = ++pixelsDone;
        if (settings.maxSeconds > 0 && elapsed() > settings.maxSeconds) {
          char message[256];
          std::snprintf(message, sizeof message,
                        "stopped after %.1f s (the time limit): %lld of %.0f pixels done, about %.3g s needed for the "
                        "whole image at this rate",
                        elapsed(), finished, pixelCount, elapsed() * pixelCount / static_cast<double>(finished));
          throw WorkLimitExceeded(message);
        }
      }
    reportProgress(progress, "path tracing", static_cast<double>(++done) / tiles);
  });
  double v = 0;
  for (const auto& p : img.pixels) v += p.vertices;
  img.meanVertices = img.pixels.empty() ? 0 : v / static_cast<double>(img.pixels.size());
  img.seconds = elapsed();
  img.truncatedPaths = truncated;
  return img;
}

std::string mediumWorkProblem(const SceneMedium& medium) {
  for (std::size_t i = 0; i < medium.particles.size(); ++i) {
    const double tau = medium.unitOpticalRadius * medium.particles[i].density;
    if (!(tau <= kMaxParticleOpticalRadius)) {
      char message[256];
      std::snprintf(message, sizeof message,
                    "particles[%zu].density: optical radius %.3g (density x extinction x radius) exceeds %g, beyond "
                    "what the path tracer can follow",
                    i, tau, kMaxParticleOpticalRadius);
      return message;
    }
  }
  return {};
}

}  // namespace cloudlut::reference
