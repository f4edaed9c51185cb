#include "bake/DirectionGrid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "bake/Quadrature.h"

namespace cloudlut::bake {

namespace {
constexpr double kPi = 3.14159265358979323846;

// An orthonormal frame (d, t, b) about the unit vector d, built from d alone.
struct FrameAbout {
  glm::dvec3 d, t, b;
  explicit FrameAbout(const glm::dvec3& dir) : d(dir) {
    const glm::dvec3 a = std::abs(d.x) < 0.7 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    t = glm::normalize(glm::cross(d, a));
    b = glm::cross(d, t);
  }
  // The unit vector at angle acos(mu) from d and azimuth ψ about it, given
  // s = √max(0, 1 − mu²), cos ψ and sin ψ: mu d + s (cos ψ t + sin ψ b).
  glm::dvec3 around(double mu, double s, double cosPsi, double sinPsi) const {
    return mu * d + s * (cosPsi * t + sinPsi * b);
  }
};
}  // namespace

DirectionGrid::DirectionGrid(int thetaNodes, int phiNodes, double grading)
    : na_(thetaNodes), nb_(phiNodes), p_(grading) {
  if (na_ < 3 || nb_ < 2 || !(p_ >= 1.0)) throw std::invalid_argument("DirectionGrid: bad size");
  theta_.resize(na_);
  for (int a = 0; a < na_; ++a) {
    const double xi = static_cast<double>(a) / (na_ - 1);
    theta_[a] = kPi * (1.0 - std::pow(1.0 - xi, p_));
  }
  theta_.back() = kPi;
  // Hat-function integrals: θ part ∫ hat_a(θ) sinθ dθ by Gauss per cell; φ part exact.
  const GaussRule& g = gaussLegendre(16);
  std::vector<double> qt(na_, 0.0);
  for (int a = 0; a + 1 < na_; ++a) {
    const double t0 = theta_[a], t1 = theta_[a + 1];
    for (int k = 0; k < 16; ++k) {
      const double t = t0 + (t1 - t0) * g.x[k], w = g.w[k] * (t1 - t0) * std::sin(t);
      qt[a] += w * (1.0 - g.x[k]);
      qt[a + 1] += w * g.x[k];
    }
  }
  const double dphi = kPi / (nb_ - 1);
  weights_.resize(static_cast<std::size_t>(count()));
  for (int a = 0; a < na_; ++a)
    for (int b = 0; b < nb_; ++b) {
      const double qp = (b == 0 || b == nb_ - 1) ? 0.5 * dphi : dphi;
      weights_[a * nb_ + b] = 2.0 * qt[a] * qp;  // both mirror halves
    }
  directions_.resize(static_cast<std::size_t>(count()));
  for (int a = 0; a < na_; ++a)
    for (int b = 0; b < nb_; ++b) {
      const double t = theta_[a], p = phi(b);
      directions_[static_cast<std::size_t>(a * nb_ + b)] = {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p),
                                                            std::cos(t)};
    }
}

double DirectionGrid::phi(int b) const { return kPi * b / (nb_ - 1); }

void DirectionGrid::locateTheta(double theta, int& a, double& f) const {
  const double x = std::clamp(theta / kPi, 0.0, 1.0);
  // (1 − x)^(1/p); pow(y, 1) is y exactly, so uniform grids skip the call
  const double xi = 1.0 - (p_ == 1.0 ? 1.0 - x : std::pow(1.0 - x, 1.0 / p_));
  const double s = xi * (na_ - 1);
  a = std::min(static_cast<int>(s), na_ - 2);
  // Linear in θ within the cell (nodes are exact θ values).
  const double t0 = theta_[a], t1 = theta_[a + 1];
  f = std::clamp((theta - t0) / (t1 - t0), 0.0, 1.0);
}

void DirectionGrid::bilinear(const glm::dvec3& w, int nodes[4], double weights[4]) const {
  const double theta = std::acos(std::clamp(w.z, -1.0, 1.0));
  const double phi = std::abs(std::atan2(w.y, w.x));
  int a, b;
  double fa, fb;
  locateTheta(theta, a, fa);
  locatePhi(phi, b, fb);
  nodes[0] = a * nb_ + b;
  nodes[1] = a * nb_ + b + 1;
  nodes[2] = (a + 1) * nb_ + b;
  nodes[3] = (a + 1) * nb_ + b + 1;
  weights[0] = (1 - fa) * (1 - fb);
  weights[1] = (1 - fa) * fb;
  weights[2] = fa * (1 - fb);
  weights[3] = fa * fb;
}

std::vector<double> phaseMatrix(const DirectionGrid& grid, const std::function<double(double)>& phase) {
  const int n = grid.count();
  std::vector<double> M(static_cast<std::size_t>(n) * n, 0.0);
  // Samples in the frame of ω_i: γ = π ξ³ (dense near the forward peak), ψ uniform.
  const int nGamma = 160, nPsi = 48;
  const GaussRule& g = gaussLegendre(8);
  std::vector<double> gam, wgam;
  for (int c = 0; c < nGamma / 8; ++c)
    for (int k = 0; k < 8; ++k) {
      const double xi = (c + g.x[k]) / (nGamma / 8);
      const double gm = kPi * xi * xi * xi;
      gam.push_back(gm);
      wgam.push_back(g.w[k] / (nGamma / 8) * 3.0 * kPi * xi * xi * std::sin(gm) * phase(std::cos(gm)));
    }
  // What every row shares: cos γ and sin γ of the samples, cos ψ and sin ψ of the azimuths.
  std::vector<double> mus(gam.size()), sines(gam.size()), cosPsi(nPsi), sinPsi(nPsi);
  for (std::size_t s = 0; s < gam.size(); ++s) {
    mus[s] = std::cos(gam[s]);
    sines[s] = std::sqrt(std::max(0.0, 1.0 - mus[s] * mus[s]));
  }
  for (int k = 0; k < nPsi; ++k) {
    const double psi = 2.0 * kPi * (k + 0.5) / nPsi;
    cosPsi[k] = std::cos(psi);
    sinPsi[k] = std::sin(psi);
  }
  tbb::parallel_for(0, n, [&](int i) {
    const FrameAbout frame(grid.direction(i));
    double* row = &M[static_cast<std::size_t>(i) * n];
    for (std::size_t s = 0; s < gam.size(); ++s) {
      for (int k = 0; k < nPsi; ++k) {
        int nodes[4];
        double w[4];
        grid.bilinear(frame.around(mus[s], sines[s], cosPsi[k], sinPsi[k]), nodes, w);
        const double base = wgam[s] * 2.0 * kPi / nPsi;
        for (int c = 0; c < 4; ++c) row[nodes[c]] += base * w[c];
      }
    }
  });
  // Conservation: Σ_i q_i M_ij = q_j.
  const auto& q = grid.nodeWeights();
  for (int j = 0; j < n; ++j) {
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += q[i] * M[static_cast<std::size_t>(i) * n + j];
    const double scale = s > 0.0 ? q[j] / s : 0.0;
    for (int i = 0; i < n; ++i) M[static_cast<std::size_t>(i) * n + j] *= scale;
  }
  return M;
}

std::vector<double> secondScatteringMatrix(const DirectionGrid& out, const DirectionGrid& fine,
                                           const std::function<double(double)>& first,
                                           const std::function<double(double)>& later) {
  const int n = out.count(), nf = fine.count();
  const int na = fine.thetaCount(), nb = fine.phiCount();
  const int sub = 4;
  const GaussRule& g = gaussLegendre(sub);
  // Sub-samples of every fine cell (both mirror halves): direction, P1·dω, and the four
  // bilinear node weights.
  struct Sample {
    glm::dvec3 w;
    double weight;  // pFirst · dω
    int nodes[4];
    double hat[4];
  };
  std::vector<Sample> samples;
  const double dphi = kPi / (nb - 1);
  for (int a = 0; a + 1 < na; ++a)
    for (int b = 0; b + 1 < nb; ++b)
      for (int i = 0; i < sub; ++i)
        for (int j = 0; j < sub; ++j) {
          const double t = fine.theta(a) + (fine.theta(a + 1) - fine.theta(a)) * g.x[i];
          const double fa = g.x[i], fb = g.x[j];
          const double dw = g.w[i] * g.w[j] * (fine.theta(a + 1) - fine.theta(a)) * dphi * std::sin(t);
          const double pf = first(-std::cos(t)) * dw;
          for (int m = 0; m < 2; ++m) {
            const double p = (m == 0 ? 1.0 : -1.0) * (fine.phi(b) + dphi * g.x[j]);
            Sample s;
            s.w = {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
            s.weight = pf;
            s.nodes[0] = a * nb + b;
            s.nodes[1] = a * nb + b + 1;
            s.nodes[2] = (a + 1) * nb + b;
            s.nodes[3] = (a + 1) * nb + b + 1;
            s.hat[0] = (1 - fa) * (1 - fb);
            s.hat[1] = (1 - fa) * fb;
            s.hat[2] = fa * (1 - fb);
            s.hat[3] = fa * fb;
            samples.push_back(s);
          }
        }
  std::vector<double> energy(nf, 0.0);
  for (const Sample& s : samples)
    for (int c = 0; c < 4; ++c) energy[s.nodes[c]] += s.weight * s.hat[c];
  std::vector<double> M(static_cast<std::size_t>(n) * nf, 0.0);
  tbb::parallel_for(0, n, [&](int i) {
    const glm::dvec3 wi = out.direction(i);
    double* row = &M[static_cast<std::size_t>(i) * nf];
    for (const Sample& s : samples) {
      const double k = later(glm::dot(wi, s.w)) * s.weight;
      for (int c = 0; c < 4; ++c) row[s.nodes[c]] += k * s.hat[c];
    }
  });
  const auto& q = out.nodeWeights();
  for (int f = 0; f < nf; ++f) {
    double s = 0.0;
    for (int i = 0; i < n; ++i) s += q[i] * M[static_cast<std::size_t>(i) * nf + f];
    const double scale = s > 0.0 ? energy[f] / s : 0.0;
    for (int i = 0; i < n; ++i) M[static_cast<std::size_t>(i) * nf + f] *= scale;
  }
  return M;
}

}  // namespace cloudlut::bake
