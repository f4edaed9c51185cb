#pragma once
// The tail of the converged multiple scattering (MultipleScattering.h): X = Σ_{n>N} J_n solves
//   (I − K) X = K·J_N,
// by restarted GMRES right-preconditioned by an isotropic coarse-space correction. The slow
// modes of dense particles are smooth, nearly isotropic diffusion modes that plain iteration
// of K would need thousands of orders for; the coarse operator K_c = R·K·P (P: an isotropic
// field on the spatial nodes, R: the angular mean) holds them, and
//   B = I + P[(I − K_c)^{-1} − I]R
// removes them. Inner products over fixed blocks (ParallelVectors.h): the result does not
// depend on the number of threads.
#include <functional>
#include <vector>

#include <Eigen/LU>

#include "bake/ScatteringOperator.h"

namespace cloudlut::bake {

// B of the header comment for fields of `field`, from K_c (NS × NS, row-major).
class CoarseCorrection {
 public:
  CoarseCorrection(const SphereField& field, const std::vector<double>& Kc);
  // out = B·in.
  void apply(const std::vector<float>& in, std::vector<float>& out) const;

 private:
  const SphereField* field_;
  int n_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;  // I − K_c, factored with partial pivoting
};

struct TailSettings {
  int restart = 24;            // Krylov vectors per cycle
  int maxApplications = 200;   // operator applications, counting those before the solve
  // Relative residual |b − (I − K)x| / |b|. The baker closes the tail's amplitude on energy;
  // against 1e-4, 3e-4 moves the converged table by < 3e-4 relative (1e-3: 1.3e-3) and saves
  // 1–3 of the 8–22 iterations.
  double tolerance = 3e-4;
};

struct TailSolution {
  std::vector<float> x;
  int iterations = 0;
  double relativeResidual = 0.0;
};

// Solves (I − K) x = b from x = 0. `applications` counts every use of K (the caller's
// before the solve included; the solve stops at settings.maxApplications); progress(f) gets
// the share of that budget used.
TailSolution solveTail(ScatteringOperator& K, const CoarseCorrection& B, const std::vector<float>& b,
                       const TailSettings& settings, int& applications,
                       const std::function<void(double)>& progress);

}  // namespace cloudlut::bake
