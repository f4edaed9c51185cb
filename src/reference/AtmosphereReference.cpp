#include "reference/AtmosphereReference.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

namespace cloudlut::reference {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kGauss = 0.28867513459481288225;  // 1 / (2 √3): two-point Gauss–Legendre nodes

// Rayleigh phase 3/(16π)(1 + ν²), sr⁻¹.
double rayleighPhase(double nu) { return 3.0 / (16.0 * kPi) * (1.0 + nu * nu); }

// Cornette–Shanks phase, sr⁻¹ (Cornette & Shanks 1992, eq. 4).
double cornetteShanks(double nu, double g) {
  const double d = 1.0 + g * g - 2.0 * g * nu;
  return 3.0 * (1.0 - g * g) * (1.0 + nu * nu) / (8.0 * kPi * (2.0 + g * g) * d * std::sqrt(d));
}

// A unit vector whose cosine with `axis` is `cosTheta`, at azimuth `phi` about it.
glm::dvec3 around(const glm::dvec3& axis, double cosTheta, double phi) {
  const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(axis, helper)), v = glm::cross(axis, u);
  const double s = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  return s * std::cos(phi) * u + s * std::sin(phi) * v + cosTheta * axis;
}

}  // namespace

AtmosphereReference::AtmosphereReference(const glsl::AtmosphereParameters& a)
    : bottom_(a.bottomRadius), top_(a.topRadius), rayleigh0_(a.rayleighScattering), ozone0_(a.ozoneAbsorption),
      rayleighH_(a.rayleighScaleHeight), mieS_(a.mieScattering), mieA_(a.mieAbsorption), mieH_(a.mieScaleHeight),
      g_(a.mieG), ozoneBottom_(a.ozoneBottom), ozonePeak_(a.ozonePeak), ozoneTop_(a.ozoneTop), albedo_(a.groundAlbedo) {}

glm::dvec3 AtmosphereReference::rayleigh(double h) const { return rayleigh0_ * std::exp(-std::max(h, 0.0) / rayleighH_); }

double AtmosphereReference::mie(double h) const { return mieS_ * std::exp(-std::max(h, 0.0) / mieH_); }

glm::dvec3 AtmosphereReference::extinction(double h) const {
  double ozone = 0.0;
  if (h > ozoneBottom_ && h < ozonePeak_) ozone = (h - ozoneBottom_) / (ozonePeak_ - ozoneBottom_);
  else if (h >= ozonePeak_ && h < ozoneTop_) ozone = (ozoneTop_ - h) / (ozoneTop_ - ozonePeak_);
  return rayleigh(h) + glm::dvec3((mieS_ + mieA_) * std::exp(-std::max(h, 0.0) / mieH_)) + ozone0_ * ozone;
}

double AtmosphereReference::distanceToTop(const glm::dvec3& p, const glm::dvec3& d) const {
  const double b = glm::dot(p, d), c = glm::dot(p, p) - top_ * top_;
  return std::max(0.0, -b + std::sqrt(std::max(0.0, b * b - c)));
}

double AtmosphereReference::distanceToGround(const glm::dvec3& p, const glm::dvec3& d) const {
  const double b = glm::dot(p, d), c = glm::dot(p, p) - bottom_ * bottom_;
  const double disc = b * b - c;
  if (b >= 0.0 || disc < 0.0) return -1.0;
  return std::max(0.0, -b - std::sqrt(disc));
}

glm::dvec3 AtmosphereReference::sunTransmittance(const glm::dvec3& p, const glm::dvec3& sun, int panels) const {
  if (distanceToGround(p, sun) >= 0.0) return glm::dvec3(0.0);
  const double L = distanceToTop(p, sun), dt = L / panels;
  glm::dvec3 tau(0.0);
  for (int i = 0; i < panels; ++i)
    for (const double o : {-kGauss, kGauss}) tau += extinction(glm::length(p + ((i + 0.5 + o) * dt) * sun) - bottom_);
  return glm::exp(-tau * (0.5 * dt));
}

glm::dvec3 AtmosphereReference::transmittanceToTop(double r, double mu, int panels) const {
  const glm::dvec3 p(0.0, r, 0.0), d(std::sqrt(std::max(0.0, 1.0 - mu * mu)), mu, 0.0);
  return sunTransmittance(p, d, panels);
}

glm::dvec3 AtmosphereReference::singleScattering(const glm::dvec3& position, const glm::dvec3& view,
                                                 const glm::dvec3& sun, int steps) const {
  return singleScattering(position, view, sun, steps, [](const glm::dvec3&) { return 1.0; });
}

glm::dvec3 AtmosphereReference::singleScattering(const glm::dvec3& position, const glm::dvec3& view,
                                                 const glm::dvec3& sun, int steps,
                                                 const std::function<double(const glm::dvec3&)>& sunVisibility) const {
  const double ground = distanceToGround(position, view);
  const double tMax = ground >= 0.0 ? ground : distanceToTop(position, view);
  const double nu = glm::dot(view, sun);
  const double pR = rayleighPhase(nu), pM = cornetteShanks(nu, g_);
  // pieces whose ends grow as u² (fine near the camera, where the air is densest for most rays),
  // each sampled at its midpoint; the optical depth is accumulated at the same resolution
  glm::dvec3 tau(0.0), L(0.0);
  for (int i = 0; i < steps; ++i) {
    const double u0 = double(i) / steps, u1 = double(i + 1) / steps, um = (i + 0.5) / steps;
    const double dt = tMax * (u1 * u1 - u0 * u0), t = tMax * um * um;
    const glm::dvec3 x = position + t * view;
    const double h = glm::length(x) - bottom_;
    const glm::dvec3 sigma = extinction(h);
    const glm::dvec3 T = glm::exp(-(tau + 0.5 * dt * sigma));
    const int panels = std::max(64, static_cast<int>(distanceToTop(x, sun) / 2000.0));
    L += T * (rayleigh(h) * pR + glm::dvec3(mie(h) * pM)) * sunTransmittance(x, sun, panels) * (sunVisibility(x) * dt);
    tau += sigma * dt;
  }
  return L;
}

AtmosphereRadiance AtmosphereReference::allOrders(const glm::dvec3& position, const glm::dvec3& view,
                                                  const glm::dvec3& sun, int paths, std::uint64_t seed) const {
  return trace(position, view, sun, paths, seed, 1, 1 << 30);
}

AtmosphereRadiance AtmosphereReference::multipleOrders(const glm::dvec3& position, const glm::dvec3& view,
                                                       const glm::dvec3& sun, int paths, std::uint64_t seed) const {
  return trace(position, view, sun, paths, seed, 2, 1 << 30);
}

AtmosphereRadiance AtmosphereReference::singleOrder(const glm::dvec3& position, const glm::dvec3& view,
                                                    const glm::dvec3& sun, int order, int paths, std::uint64_t seed) const {
  return trace(position, view, sun, paths, seed, order, order);
}

AtmosphereRadiance AtmosphereReference::trace(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun,
                                              int paths, std::uint64_t seed, int firstScored, int lastScored) const {
  AtmosphereRadiance out{glm::dvec3(0.0), glm::dvec3(0.0)};
  for (int c = 0; c < 3; ++c) {
    std::mt19937_64 rng(seed * 3 + static_cast<std::uint64_t>(c));
    std::uniform_real_distribution<double> U(0.0, 1.0);
    // a majorant of σt over the shell: every constituent at its densest
    const double majorant = rayleigh0_[c] + mieS_ + mieA_ + ozone0_[c];
    double sum = 0.0, sumSq = 0.0;
    for (int n = 0; n < paths; ++n) {
      glm::dvec3 p = position, d = view;
      double weight = 1.0, radiance = 0.0;
      for (int bounce = 0; bounce < 200 && bounce < lastScored; ++bounce) {
        const bool scored = bounce + 1 >= firstScored;  // this vertex's next-event estimate is order bounce + 1
        const double ground = distanceToGround(p, d);
        const double tEnd = ground >= 0.0 ? ground : distanceToTop(p, d);
        // delta tracking to the next real collision, or to the boundary
        double t = 0.0;
        bool collided = false;
        while (true) {
          t -= std::log(1.0 - U(rng)) / majorant;
          if (t >= tEnd) break;
          if (U(rng) * majorant < extinction(glm::length(p + t * d) - bottom_)[c]) { collided = true; break; }
        }
        if (!collided && ground < 0.0) break;  // left the atmosphere
        if (!collided) {
          // Lambertian ground: next-event estimate toward the sun, then a cosine-weighted bounce
          p = p + tEnd * d;
          const glm::dvec3 normal = glm::normalize(p);
          p = normal * bottom_;
          const double cosSun = glm::dot(normal, sun);
          if (cosSun > 0.0 && scored) radiance += weight * albedo_[c] / kPi * cosSun * sunTransmittance(p, sun, 400)[c];
          weight *= albedo_[c];
          // cosine-weighted: the azimuth drawn first, then the cosine, as two statements (as
          // arguments of one call their order would be the compiler's)
          const double azimuth = 2.0 * kPi * U(rng);
          const double cosine = std::sqrt(U(rng));
          d = around(normal, cosine, azimuth);
        } else {
          p = p + t * d;
          const double h = glm::length(p) - bottom_;
          const double sR = rayleigh(h)[c], sM = mie(h), sT = extinction(h)[c];
          weight *= (sR + sM) / sT;  // survival of absorption by Mie and ozone
          const double nuSun = glm::dot(d, sun);
          const double phase = (sR * rayleighPhase(nuSun) + sM * cornetteShanks(nuSun, g_)) / (sR + sM);
          if (scored) radiance += weight * phase * sunTransmittance(p, sun, 400)[c];
          // the next direction: Rayleigh or Mie by their share, each phase by rejection (both are
          // bounded by a constant times uniform and Henyey–Greenstein respectively)
          double cosTheta;
          if (U(rng) * (sR + sM) < sR) {
            do cosTheta = 2.0 * U(rng) - 1.0; while (U(rng) * 2.0 > 1.0 + cosTheta * cosTheta);
          } else {
            do {
              const double s = (1.0 - g_ * g_) / (1.0 - g_ + 2.0 * g_ * U(rng));
              cosTheta = std::clamp((1.0 + g_ * g_ - s * s) / (2.0 * g_), -1.0, 1.0);
            } while (U(rng) * 2.0 > 1.0 + cosTheta * cosTheta);
          }
          d = around(d, cosTheta, 2.0 * kPi * U(rng));
        }
        if (bounce >= 8) {  // Russian roulette, unbiased
          if (U(rng) < 0.5) break;
          weight *= 2.0;
        }
      }
      sum += radiance;
      sumSq += radiance * radiance;
    }
    const double mean = sum / paths;
    out.value[c] = mean;
    out.standardError[c] = std::sqrt(std::max(0.0, sumSq / paths - mean * mean) / paths);
  }
  return out;
}

}  // namespace cloudlut::reference
