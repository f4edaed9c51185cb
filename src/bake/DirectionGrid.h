#pragma once
// Grids of directions in the light frame (pole +l) of an axially symmetric light field, and
// the phase-function matrices that act on radiance sampled on them.
//
// A field sampled at a point of the meridian plane (y = 0) is symmetric under the mirror
// y → −y, so a grid needs only the azimuths φ ∈ [0, π]: nodes (θ_a, φ_b), θ graded as
// θ(ξ) = π(1 − (1 − ξ)^p) on uniform ξ (p = 1 uniform; p > 1 refines toward θ = π, the
// direction sunlight travels), φ uniform. Between nodes a field is bilinear in (θ, φ).
#include <algorithm>
#include <functional>
#include <vector>

#include <glm/vec3.hpp>

namespace cloudlut::bake {

class DirectionGrid {
 public:
  DirectionGrid() = default;
  DirectionGrid(int thetaNodes, int phiNodes, double grading);

  int thetaCount() const { return na_; }
  int phiCount() const { return nb_; }
  int count() const { return na_ * nb_; }
  double theta(int a) const { return theta_[a]; }
  double phi(int b) const;
  // The unit direction of node (a, b), (sin θ cos φ, sin θ sin φ, cos θ); of node i = a·nb + b.
  const glm::dvec3& direction(int a, int b) const { return directions_[static_cast<std::size_t>(a * nb_ + b)]; }
  const glm::dvec3& direction(int i) const { return directions_[static_cast<std::size_t>(i)]; }

  // Lower node and fraction along θ for a zenith angle in [0, π].
  void locateTheta(double theta, int& a, double& f) const;
  // Lower node and fraction along φ for a folded azimuth in [0, π].
  void locatePhi(double phi, int& b, double& f) const {  // inline: once per stencil point
    const double s = std::clamp(phi / 3.14159265358979323846, 0.0, 1.0) * (nb_ - 1);
    b = std::min(static_cast<int>(s), nb_ - 2);
    f = s - b;
  }
  // Bilinear weights of direction w: four (node, weight) pairs.
  void bilinear(const glm::dvec3& w, int nodes[4], double weights[4]) const;

  // ∫ hat_i dω over the whole sphere (both mirror halves): the quadrature weight of node i.
  const std::vector<double>& nodeWeights() const { return weights_; }

 private:
  int na_ = 0, nb_ = 0;
  double p_ = 1.0;
  std::vector<double> theta_, weights_;
  std::vector<glm::dvec3> directions_;  // every node's direction, computed once (the bake reads them per ray)
};

// Phase-function convolution on a grid: out[i] = Σ_j M[i·n + j] in[j] approximates
// ∫ p(ω_i · ω') f(ω') dω' for f bilinear on the grid; integrated in the frame of ω_i with
// samples graded toward the forward peak, so sharp phase functions are resolved. Columns are
// renormalised so that Σ_i q_i M_ij = q_j: scattering conserves energy exactly.
// `phase(mu)` is the phase function (sr⁻¹) of the cosine of the scattering angle.
std::vector<double> phaseMatrix(const DirectionGrid& grid, const std::function<double(double)>& phase);

// Second scattering of sunlight: out[i] = Σ_f M[i·nf + f] a[f] approximates
// ∫ pLater(ω_i·ω') pFirst(−l·ω') a(ω') dω' for a bilinear on the fine grid (sunlight travels
// along −l, θ = π). Columns renormalised to the energy ∫ pFirst(−l·ω') hat_f dω' each carries.
std::vector<double> secondScatteringMatrix(const DirectionGrid& out, const DirectionGrid& fine,
                                           const std::function<double(double)>& first,
                                           const std::function<double(double)>& later);

}  // namespace cloudlut::bake
