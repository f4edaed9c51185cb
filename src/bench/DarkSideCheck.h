#pragma once
// The converged tables' dark side against forward photon tracing (reference/PhotonExitTally.h):
// for each bin, the bin mean of the tables' scattered radiance
//   L(S, v) = P1(v·l) · L1(S, v, ρ) + LM(S, v, ρ)   (sr⁻¹ per unit sun irradiance;
//   seed §4.4's single and multiple terms, decoded by core/TableLookup.h)
// beside the photons' tally of the same bin. Used by the scattering bench and its test.
#include <cstdint>
#include <vector>

#include "core/Table4D.h"
#include "reference/PhotonExitTally.h"

namespace cloudlut::bench {

struct DarkSideBinResult {
  double table = 0, photons = 0, se = 0;  // sr⁻¹; se: the tally's standard error
  double relativeError() const { return photons > 0 ? table / photons - 1.0 : 0.0; }
};

struct DarkSideComparison {
  std::vector<DarkSideBinResult> bins;
  double medianAbsError = 0;  // median over the bins of |table/photons − 1|
  double worstError = 0;      // the signed relative error of largest magnitude
  double worstSe = 0;         // that bin's relative standard error
  double tallySeconds = 0;
};

// Compares the tables at density scale rho (optical radius ρσ, σ = the tables' unit optical
// radius) with `photons` forward photons of the tables' phase functions (the defaults').
DarkSideComparison compareDarkSide(const Table4D& single, const Table4D& multiple, double rho,
                                   const std::vector<reference::ExitBin>& bins, long long photons,
                                   std::uint64_t seed);

}  // namespace cloudlut::bench
