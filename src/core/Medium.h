#pragma once
// The medium a particle list describes: the density model (and its seed) of every particle's
// reference particle, the extinction β and radius R that make its optical radius, and the phase
// functions of the first and of every later scattering. The path-traced reference, the ray
// marcher and the ground-truth bench render the same medium; io/LutSetMedium.h reads it from a
// LUT set's manifest.
#include <cstdint>
#include <string>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/ReferenceParticle.h"

namespace cloudlut {

struct Medium {
  DensityModel model = DensityModel::Noise;
  std::uint64_t seed = 1;
  double extinction = defaults::kExtinctionPerMetre;  // β, 1/m
  double radius = defaults::kParticleRadiusMetres;    // R, m
  Phase first = defaults::kFirstPhase, later = defaults::kLaterPhase;
  std::string source = "defaults";  // where it came from, for messages
  // σ of a particle of density scale 1 in unit-sphere units: β·R (dimensionless).
  double unitOpticalRadius() const { return extinction * radius; }
};

}  // namespace cloudlut
