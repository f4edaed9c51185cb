#pragma once
// A brute-force CPU integration of the atmosphere (lut_formats/glsl/cloudlut_atmosphere.glsl's
// model), independent of the tables and of the shared GLSL's integrators: it shares only the
// parameter values and re-implements densities, phases and geometry in double precision.
//   transmittance: composite Gauss–Legendre quadrature of the extinction along the ray;
//   single scattering: quadrature along the view ray, each sample lit through a quadrature of
//     the extinction toward the sun (a point sun of unit irradiance; Bruneton & Neyret 2008 eq. 4);
//   all orders: Monte Carlo path tracing from the camera (delta tracking, next-event estimation
//     toward the sun at every vertex, Lambertian ground), one colour channel at a time.
// Radiance is per unit sun irradiance (sr⁻¹). Positions are relative to the planet's centre, m.
#include <cstdint>
#include <functional>

#include <glm/vec3.hpp>

#include "core/Glsl.h"

namespace cloudlut::reference {

struct AtmosphereRadiance {
  glm::dvec3 value;         // radiance, sr⁻¹ per unit sun irradiance (R, G, B)
  glm::dvec3 standardError; // of the Monte Carlo estimate (0 for quadratures)
};

class AtmosphereReference {
 public:
  explicit AtmosphereReference(const glsl::AtmosphereParameters& parameters);

  // Transmittance from radius r (m) along zenith cosine mu to the top of the atmosphere (0 when
  // the ray meets the ground), by `panels` Gauss–Legendre panels (Bruneton & Neyret 2008 eq. 3).
  glm::dvec3 transmittanceToTop(double r, double mu, int panels = 4000) const;

  // Single-scattered radiance seen from `position` (m, from the centre) along the unit `view`
  // with the sun toward unit `sun`, to the ground or the top, by `steps` pieces along the ray.
  glm::dvec3 singleScattering(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun,
                              int steps = 2000) const;

  // The same with the sunlight reaching each point x (m, from the centre) scaled by
  // sunVisibility(x) ∈ [0, 1], a shadow cast by something other than the air (a cloud's).
  glm::dvec3 singleScattering(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun, int steps,
                              const std::function<double(const glm::dvec3&)>& sunVisibility) const;

  // Radiance of all orders (sky only, not the sun's disc), by `paths` paths per channel.
  AtmosphereRadiance allOrders(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun,
                               int paths, std::uint64_t seed) const;

  // Radiance of the orders >= 2 only (light scattered at least twice, or reflected by the ground
  // and scattered, before it reaches the camera), by the same paths without the next-event
  // estimate at their first vertex. Adding singleScattering (a quadrature, no noise) gives all
  // orders with the Monte Carlo noise of the multiply-scattered share alone.
  AtmosphereRadiance multipleOrders(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun,
                                    int paths, std::uint64_t seed) const;

  // Radiance of scattering order `order` alone (>= 2; a ground reflection counts as an order),
  // by the same paths scored only at their (order − 1)-th vertex and stopped there: where the
  // orders >= 2 go wrong, order by order.
  AtmosphereRadiance singleOrder(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun, int order,
                                 int paths, std::uint64_t seed) const;

  // Extinction and scattering coefficients at altitude h (m), m⁻¹.
  glm::dvec3 extinction(double h) const;
  glm::dvec3 rayleigh(double h) const;
  double mie(double h) const;

 private:
  // Distance from p along unit d to the top (> 0) and to the ground (< 0 when missed), m.
  double distanceToTop(const glm::dvec3& p, const glm::dvec3& d) const;
  double distanceToGround(const glm::dvec3& p, const glm::dvec3& d) const;
  // Transmittance from p toward the unit sun direction (0 when the ground hides it).
  glm::dvec3 sunTransmittance(const glm::dvec3& p, const glm::dvec3& sun, int panels) const;
  // The path tracer behind allOrders, multipleOrders and singleOrder: it scores the next-event
  // estimates of the orders firstScored … lastScored (order n at the path's n-th vertex) and
  // stops after lastScored.
  AtmosphereRadiance trace(const glm::dvec3& position, const glm::dvec3& view, const glm::dvec3& sun, int paths,
                           std::uint64_t seed, int firstScored, int lastScored) const;

  double bottom_, top_;
  glm::dvec3 rayleigh0_, ozone0_;
  double rayleighH_, mieS_, mieA_, mieH_, g_;
  double ozoneBottom_, ozonePeak_, ozoneTop_;
  glm::dvec3 albedo_;
};

}  // namespace cloudlut::reference
