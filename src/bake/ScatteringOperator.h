#pragma once
// The operator K = M·T that maps the source of one scattering order to the next in the fast
// multiple-scattering method (MultipleScattering.h), on a SphereField:
//   T (transport): L(x, ω) = ∫_0^{d(x, −ω)} σ e^{−σs} J(x − sω, ω) ds at every node x and direction
//     ω, by attenuatedRayRule; J is read at the direction's own zenith node and interpolated
//     in space (SphereField::locate). The K points of every (node, direction) ray are a
//     stencil built once per density and reused by every order; points of zero weight (the
//     far panel of a short ray) are left out of it.
//   M (phase convolution): J'(x, ω) = Σ_ω' M(ω, ω') L(x, ω'), one dense matrix product.
#include <cstdint>
#include <memory>
#include <vector>

#include "bake/RecycledArrays.h"
#include "bake/SphereField.h"

namespace cloudlut::bake {

// out(s, i) = Σ_j Mt[j·outDirs + i] · in(s, j) at every spatial node s of `field`, both in the
// field's layout (SphereField.h): in with inDirs directions per node, out with outDirs; Mt is
// inDirs × outDirs row-major (a phase matrix transposed).
void convolvePhase(const std::vector<float>& in, int inDirs, const std::vector<float>& Mt, int outDirs,
                   const SphereField& field, std::vector<float>& out);

class TransportStencil {
 public:
  // One quadrature point of a ray: where it reads the field and with which weights.
  struct Entry {
    std::uint32_t base;  // node (radial start, zenith start, direction zenith, azimuth)
    float wr[4];         // radial weights × quadrature weight
    float wt[4];         // position-zenith weights
    float fb;            // azimuth fraction
  };
  // Where stencils keep their entries between density slices (about 10⁸ bytes each).
  using Storage = RecycledArrays<Entry>;

  // Quadrature points per ray of the stencil for optical radius σ and `points` requested (the
  // rule may round up).
  static int pointsPerRay(double sigma, int points);

  // The stencil of T for optical radius σ with `points` quadrature points per ray (the rule
  // may round up), its entries leased from `storage`, which must outlive it.
  TransportStencil(const SphereField& field, double sigma, int points, Storage& storage);

  // out = T·in (fields of field.size() values).
  void apply(const std::vector<float>& in, std::vector<float>& out) const;

  // The isotropic coarse operator K_c = R·K·P, NS × NS row-major: P spreads a value per
  // spatial node over every direction, R takes the angular mean Σ_d q_d/(4π) with the direction
  // grid's node weights q. M conserves the angular mean, so R·M·T·P = R·T·P.
  std::vector<double> isotropicCoarseOperator() const;

 private:
  const SphereField* field_;
  int K_ = 0;
  // K per (node, direction) in the field's order; not cleared (an earlier slice's values may
  // be there): only the first counts_[cell] of a cell are written and read.
  Storage::Lease entries_;
  std::vector<std::uint8_t> counts_;  // points of nonzero weight per cell (packed first)
};

// K = M·T on a field, with its own scratch space for T·in.
class ScatteringOperator {
 public:
  // Mt: the later phase matrix transposed (D × D); both references must outlive the operator.
  ScatteringOperator(const TransportStencil& transport, const std::vector<float>& Mt, const SphereField& field);
  // out = K·in.
  void apply(const std::vector<float>& in, std::vector<float>& out);
  const TransportStencil& transport() const { return *transport_; }

 private:
  const TransportStencil* transport_;
  const std::vector<float>* Mt_;
  const SphereField* field_;
  std::vector<float> scratch_;
};

}  // namespace cloudlut::bake
