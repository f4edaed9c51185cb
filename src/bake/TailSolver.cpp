#include "bake/TailSolver.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bake/ParallelVectors.h"

namespace cloudlut::bake {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

CoarseCorrection::CoarseCorrection(const SphereField& field, const std::vector<double>& Kc)
    : field_(&field), n_(field.nodeCount()) {
  // LU of I − K_c with partial pivoting (Eigen, serial: deterministic, NS³/3 flops).
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> K(Kc.data(), n_, n_);
  lu_.compute(Eigen::MatrixXd::Identity(n_, n_) - K);
}

void CoarseCorrection::apply(const std::vector<float>& in, std::vector<float>& out) const {
  // R·in: the angular mean per spatial node; then the correction P[(I − K_c)^{-1} − I]R.
  const int NS = n_, D = field_->directionCount();
  const std::vector<double>& q = field_->directions().nodeWeights();
  const double inv4pi = 1.0 / (4.0 * kPi);
  std::vector<double> mean(static_cast<std::size_t>(NS), 0.0);
  tbb::parallel_for(0, NS, [&](int sIdx) {
    double m = 0.0;
    for (int dd = 0; dd < D; ++dd) m += q[dd] * in[field_->index(sIdx, dd)];
    mean[sIdx] = m * inv4pi;
  });
  const Eigen::VectorXd corr = lu_.solve(Eigen::Map<const Eigen::VectorXd>(mean.data(), NS));
  tbb::parallel_for(0, NS, [&](int sIdx) {
    const float c = static_cast<float>(corr[sIdx] - mean[sIdx]);
    for (int dd = 0; dd < D; ++dd) {
      const std::size_t i = field_->index(sIdx, dd);
      out[i] = in[i] + c;
    }
  });
}

TailSolution solveTail(ScatteringOperator& K, const CoarseCorrection& B, const std::vector<float>& b,
                       const TailSettings& settings, int& applications,
                       const std::function<void(double)>& progress) {
  const std::size_t N = b.size();
  const int m = settings.restart, maxApplications = settings.maxApplications;
  const double tol = settings.tolerance;
  // out = (I − K)·z, leaving K·z in out first.
  const auto applyA = [&](const std::vector<float>& z, std::vector<float>& out) {
    K.apply(z, out);
    ++applications;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N, 8192), [&](const auto& rg) {
      for (std::size_t i = rg.begin(); i < rg.end(); ++i) out[i] = z[i] - out[i];
    });
  };
  TailSolution sol;
  std::vector<float> x(N, 0.0f), r = b, w(N), z(N);
  const double bnorm = std::sqrt(dot(b, b));
  double rnorm = bnorm;
  while (bnorm > 0.0 && rnorm > tol * bnorm && applications < maxApplications) {
    // One cycle: Arnoldi on A·B (modified Gram–Schmidt) with Givens rotations of the
    // Hessenberg matrix H; g holds the rotated residual, |g[k+1]| the residual norm.
    std::vector<std::vector<float>> V(1, r);
    const float inv = static_cast<float>(1.0 / rnorm);
    for (float& v : V[0]) v *= inv;
    std::vector<std::vector<double>> H(m + 1, std::vector<double>(m, 0.0));
    std::vector<double> cs(m), sn(m), g(m + 1, 0.0);
    g[0] = rnorm;
    int k = 0;
    for (; k < m && applications < maxApplications; ++k) {
      B.apply(V[k], z);
      applyA(z, w);
      ++sol.iterations;
      for (int j = 0; j <= k; ++j) {
        H[j][k] = dot(w, V[j]);
        axpy(static_cast<float>(-H[j][k]), V[j], w);
      }
      H[k + 1][k] = std::sqrt(dot(w, w));
      for (int j = 0; j < k; ++j) {
        const double t = cs[j] * H[j][k] + sn[j] * H[j + 1][k];
        H[j + 1][k] = -sn[j] * H[j][k] + cs[j] * H[j + 1][k];
        H[j][k] = t;
      }
      const double hk1 = H[k + 1][k];
      const double den = std::hypot(H[k][k], hk1);
      cs[k] = den > 0 ? H[k][k] / den : 1.0;
      sn[k] = den > 0 ? hk1 / den : 0.0;
      H[k][k] = den;
      H[k + 1][k] = 0.0;
      g[k + 1] = -sn[k] * g[k];
      g[k] = cs[k] * g[k];
      rnorm = std::abs(g[k + 1]);
      if (rnorm <= tol * bnorm || !(hk1 > 0.0)) {
        ++k;
        break;
      }
      std::vector<float> vn(N);
      const float invh = static_cast<float>(1.0 / hk1);
      for (std::size_t i = 0; i < N; ++i) vn[i] = w[i] * invh;
      V.push_back(std::move(vn));
    }
    // The triangular system H y = g; x += B·(V y).
    std::vector<double> y(k, 0.0);
    for (int i = k - 1; i >= 0; --i) {
      double t = g[i];
      for (int j = i + 1; j < k; ++j) t -= H[i][j] * y[j];
      y[i] = H[i][i] != 0.0 ? t / H[i][i] : 0.0;
    }
    std::fill(z.begin(), z.end(), 0.0f);
    for (int j = 0; j < k; ++j) axpy(static_cast<float>(y[j]), V[j], z);
    B.apply(z, w);
    axpy(1.0f, w, x);
    // True residual r = b − (I − K) x = b − x + K x.
    K.apply(x, w);
    ++applications;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N, 8192), [&](const auto& rg) {
      for (std::size_t i = rg.begin(); i < rg.end(); ++i) r[i] = b[i] - x[i] + w[i];
    });
    rnorm = std::sqrt(dot(r, r));
    progress(std::min(1.0, static_cast<double>(applications) / maxApplications));
  }
  sol.x = std::move(x);
  sol.relativeResidual = bnorm > 0 ? rnorm / bnorm : 0.0;
  return sol;
}

}  // namespace cloudlut::bake
