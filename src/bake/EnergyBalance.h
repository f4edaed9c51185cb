#pragma once
// Where the sunlight falling on a homogeneous particle goes: the share of the incident power
// (π for unit irradiance on the unit sphere's cross-section) that leaves it unscattered,
// singly scattered and multiply scattered, per density slice of the scattering tables.
//
//   unscattered = (1 − e^{−2σ}(1 + 2σ)) / (2σ²)            (closed form from the chord lengths)
//   single      = (1/π) ∫_sphere ∫_{v·S<0} P1(v·l) L1(S, v) cos θv dω dA
//   multiple    = (1/π) ∫_sphere ∫_{v·S<0} LM(S, v) cos θv dω dA
// The tables are read with the renderer's interpolation (Table4D::sample at the node density
// of each slice); directions are integrated about l, graded toward the sun where P1 peaks.
// A non-absorbing particle returns everything: total = 1 when LM holds every order.
#include <vector>

#include <nlohmann/json.hpp>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

struct EnergySlice {
  double rho = 0;          // density scale 2^s of the slice
  double sigma = 0;        // optical radius
  double unscattered = 0;  // shares of the incident power
  double single = -1;      // −1 when the table was not given
  double multiple = -1;
  double total = 0;        // sum of the shares present
};

struct EnergyBalance {
  std::vector<EnergySlice> slices;
  nlohmann::json toJson() const;  // {"slices": [{rho, sigma, unscattered, single, multiple, total}...]}
};

struct EnergyInputs {
  double unitOpticalRadius = defaults::kUnitOpticalRadius;  // σ of ρ = 1: extinction · radius
  Phase firstPhase = defaults::kFirstPhase;                 // P1
};

// Parameters from the tables' own "parameters" (extinction_per_m, radius_m, first_phase),
// as written by bakeScattering. Either table may be null (not both); both must share axes.
EnergyInputs energyInputsFromParameters(const Table4D* single, const Table4D* multiple);

EnergyBalance computeEnergyBalance(const Table4D* single, const Table4D* multiple,
                                   const EnergyInputs& inputs);
inline EnergyBalance computeEnergyBalance(const Table4D* single, const Table4D* multiple) {
  return computeEnergyBalance(single, multiple, energyInputsFromParameters(single, multiple));
}

// Closed-form share of the incident power crossing the sphere of optical radius σ unscattered.
double unscatteredShareExact(double sigma);

}  // namespace cloudlut::bake
