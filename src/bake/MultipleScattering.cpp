#include "bake/MultipleScattering.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bake/DirectionGrid.h"
#include "bake/Quadrature.h"
#include "core/Glsl.h"

namespace cloudlut::bake {

namespace {

constexpr double kPi = 3.14159265358979323846;

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::function<double(double)> phaseOf(const Phase& p) {
  return [p](double mu) { return static_cast<double>(phaseValue(p, static_cast<float>(mu))); };
}

// Depth-graded radial axis: node i of n at q = i/(n−1), with
//   q(δ) = α δ + (1 − α) ln(1 + A δ) / ln(1 + A),   δ = 1 − r (depth below the surface):
// logarithmic near the surface (the boundary layer of the field is a few mean free paths thick,
// with a logarithmic-derivative profile) and at least α-linear in the interior.
struct RadialAxis {
  int n = 2;
  double A = 0.0, alpha = 1.0, logA = 1.0;
  std::vector<double> radii;
  RadialAxis(int nodes, double a, double linearShare)
      : n(nodes), A(a), alpha(a > 1e-9 ? linearShare : 1.0), logA(a > 1e-9 ? std::log1p(a) : 1.0) {
    radii.resize(n);
    for (int i = 0; i < n; ++i) {
      const double target = static_cast<double>(i) / (n - 1);
      double lo = 0.0, hi = 1.0;
      for (int it = 0; it < 80; ++it) {
        const double mid = 0.5 * (lo + hi);
        (qOfDepth(mid) < target ? lo : hi) = mid;
      }
      radii[i] = i == 0 ? 1.0 : (i == n - 1 ? 0.0 : 1.0 - 0.5 * (lo + hi));
    }
  }
  double qOfDepth(double d) const {
    return A > 1e-9 ? alpha * d + (1.0 - alpha) * std::log1p(A * d) / logA : d;
  }
  double q(double r) const { return qOfDepth(std::clamp(1.0 - r, 0.0, 1.0)); }
  double radius(int i) const { return radii[i]; }
  void locate(double r, int& i, float& f) const {
    const double s = q(r) * (n - 1);
    i = std::min(static_cast<int>(s), n - 2);
    f = static_cast<float>(std::clamp(s - i, 0.0, 1.0));
  }
  // Four-node weights in q (see cubicWeights).
  void cubic(double r, int& start, float w[4]) const;
};

// Four-node interpolation weights at the continuous node coordinate x ∈ [0, n−1] of a uniform
// axis of n ≥ 4 nodes: nodes start … start+3, exact for quadratics — Catmull–Rom inside,
// three-point Lagrange in the first and last intervals. Linear interpolation of a curved field
// in an optically thick medium acts like extra diffusion (it widens every step of the random
// walk to the grid spacing); quadratic exactness removes that leading error.
void cubicWeights(double x, int n, int& start, float w[4]) {
  const int i = std::clamp(static_cast<int>(x), 0, n - 2);
  const double f = std::clamp(x - i, 0.0, 1.0);
  if (i == 0) {
    start = 0;
    w[0] = static_cast<float>((f - 1) * (f - 2) / 2);
    w[1] = static_cast<float>(-f * (f - 2));
    w[2] = static_cast<float>(f * (f - 1) / 2);
    w[3] = 0.0f;
  } else if (i == n - 2) {
    start = n - 4;
    const double y = f + 1.0;  // relative to node n − 3
    w[0] = 0.0f;
    w[1] = static_cast<float>((y - 1) * (y - 2) / 2);
    w[2] = static_cast<float>(-y * (y - 2));
    w[3] = static_cast<float>(y * (y - 1) / 2);
  } else {
    start = i - 1;
    const double f2 = f * f, f3 = f2 * f;
    w[0] = static_cast<float>((-f3 + 2 * f2 - f) / 2);
    w[1] = static_cast<float>((3 * f3 - 5 * f2 + 2) / 2);
    w[2] = static_cast<float>((-3 * f3 + 4 * f2 + f) / 2);
    w[3] = static_cast<float>((f3 - f2) / 2);
  }
}

void RadialAxis::cubic(double r, int& start, float w[4]) const { cubicWeights(q(r) * (n - 1), n, start, w); }

// Quadrature along a ray: ∫_0^d σe^{−σs} f(s) ds ≈ Σ w f(s). Near part (the first three mean
// free paths, where the attenuation dominates) in u = 1 − e^{−σs} on the panels
// [0, U₁/8] and [U₁/8, U₁], U₁ = 1 − e^{−min(σd, 6)}; far part (s > 6/σ) in s itself, where
// the source may grow as fast as the light decays (light crossing the particle toward its dark
// side) and u would crowd it into a singular corner. pts = points per panel. Dense particles
// (σ ≥ kFarPanelMaxSigma) use u over the whole ray: panels [0, U/16], [U/16, U/4], [U/4, U].
constexpr double kNearOpticalDepth = 6.0;
// Optical radius from which the far panel is dropped (see rayRule).
constexpr double kFarPanelMaxSigma = 20.0;

void rayRule(double sigma, double length, int total, std::vector<double>& s, std::vector<double>& w) {
  s.clear();
  w.clear();
  length = std::max(length, 0.0);
  const double tau = sigma * length;
  int pts[3];
  if (sigma >= kFarPanelMaxSigma) {
    // Dense: the far part carries nothing but a leak; all points in u (its far mass sits
    // within a few mean free paths, where it belongs for the diffusion modes).
    pts[0] = std::max(2, total / 4);
    pts[1] = std::max(2, total / 4);
    pts[2] = std::max(2, total - pts[0] - pts[1]);
    const double U = -std::expm1(-tau);
    const double edges[4] = {0.0, U / 16.0, U / 4.0, U};
    for (int p = 0; p < 3; ++p) {
      const GaussRule& g = gaussLegendre(pts[p]);
      const double a = edges[p], h = edges[p + 1] - edges[p];
      for (int k = 0; k < pts[p]; ++k) {
        const double u = a + h * g.x[k];
        s.push_back(std::min(-std::log1p(-u) / sigma, length));
        w.push_back(h * g.w[k]);
      }
    }
    return;
  }
  pts[0] = std::max(2, total / 5);
  pts[2] = std::max(2, total / 4);
  pts[1] = std::max(2, total - pts[0] - pts[2]);
  const double tauNear = std::min(tau, kNearOpticalDepth);
  const double U1 = -std::expm1(-tauNear);
  const double edges[3] = {0.0, U1 / 8.0, U1};
  for (int p = 0; p < 2; ++p) {
    const GaussRule& g = gaussLegendre(pts[p]);
    const double a = edges[p], h = edges[p + 1] - edges[p];
    for (int k = 0; k < pts[p]; ++k) {
      const double u = a + h * g.x[k];
      s.push_back(std::min(-std::log1p(-u) / sigma, length));
      w.push_back(h * g.w[k]);
    }
  }
  const GaussRule& g = gaussLegendre(pts[2]);
  const double s0 = tauNear / sigma, h = length - s0;
  const std::size_t first = w.size();
  double sum = 0.0;
  for (int k = 0; k < pts[2]; ++k) {
    const double sk = s0 + h * g.x[k];
    s.push_back(sk);
    w.push_back(tau > tauNear ? h * g.w[k] * sigma * std::exp(-sigma * sk) : 0.0);
    sum += w.back();
  }
  // The far weights must carry exactly the far mass e^{−τ_near} − e^{−τ}: conservation of the
  // discrete operator (a lost 10⁻³ per order would drain dense particles' slow modes).
  const double mass = tau > tauNear ? std::exp(-tauNear) - std::exp(-tau) : 0.0;
  if (sum > 0.0)
    for (std::size_t k = first; k < w.size(); ++k) w[k] *= mass / sum;
  else if (mass > 0.0)
    w[first] = mass;
}


// Deterministic inner product: fixed 4096-element blocks summed in order.
double dot(const std::vector<float>& a, const std::vector<float>& b) {
  const std::size_t n = a.size(), block = 4096, nb = (n + block - 1) / block;
  std::vector<double> part(nb, 0.0);
  tbb::parallel_for(std::size_t(0), nb, [&](std::size_t k) {
    double s = 0.0;
    const std::size_t e = std::min(n, (k + 1) * block);
    for (std::size_t i = k * block; i < e; ++i) s += static_cast<double>(a[i]) * b[i];
    part[k] = s;
  });
  double s = 0.0;
  for (double p : part) s += p;
  return s;
}

void axpy(float alpha, const std::vector<float>& x, std::vector<float>& y) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, y.size(), 8192), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) y[i] += alpha * x[i];
  });
}

struct StencilEntry {
  std::uint32_t base;  // node (radial start, zenith start, direction zenith, azimuth)
  float wr[4];         // radial weights × quadrature weight
  float wt[4];         // position-zenith weights
  float fb;            // azimuth fraction
};

}  // namespace

struct FastMultipleScattering::Shared {
  ScatteringSettings settings;
  FastResolution res;
  DirectionGrid coarse, fine;
  std::vector<float> Mt;   // D × D: Mt[j·D + i] = M[i][j]
  std::vector<float> M2t;  // F × D: M2t[f·D + i] = M2[i][f]
};

FastMultipleScattering::FastMultipleScattering(const ScatteringSettings& settings,
                                               const FastResolution& res)
    : shared_(new Shared) {
  Shared& sh = *shared_;
  sh.settings = settings;
  sh.res = res;
  sh.coarse = DirectionGrid(res.dirTheta, res.dirPhi, 1.0);
  sh.fine = DirectionGrid(res.fineTheta, res.finePhi, 2.0);
  const auto later = phaseOf(settings.laterPhase), first = phaseOf(settings.firstPhase);
  const std::vector<double> M = phaseMatrix(sh.coarse, later);
  const std::vector<double> M2 = secondScatteringMatrix(sh.coarse, sh.fine, first, later);
  const int D = sh.coarse.count(), F = sh.fine.count();
  sh.Mt.resize(static_cast<std::size_t>(D) * D);
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j)
      sh.Mt[static_cast<std::size_t>(j) * D + i] = static_cast<float>(M[static_cast<std::size_t>(i) * D + j]);
  sh.M2t.resize(static_cast<std::size_t>(F) * D);
  for (int i = 0; i < D; ++i)
    for (int f = 0; f < F; ++f)
      sh.M2t[static_cast<std::size_t>(f) * D + i] = static_cast<float>(M2[static_cast<std::size_t>(i) * F + f]);
}

FastMultipleScattering::~FastMultipleScattering() { delete shared_; }

void FastMultipleScattering::bakeSlice(double sigma, int slice, Table4D& table, Table4D* tailTable,
                                       nlohmann::json& report,
                                       const ProgressFn& progress, double progressBase,
                                       double progressSpan) const {
  const Shared& sh = *shared_;
  const FastResolution& res = sh.res;
  const int nr = res.radial, nt = res.zenith;
  const int nb = sh.coarse.phiCount();
  const int D = sh.coarse.count(), F = sh.fine.count();
  const int NS = nr * nt;
  const std::size_t N = static_cast<std::size_t>(NS) * D;
  const RadialAxis radial(nr, res.grading * sigma, res.linearShare);
  const glm::dvec3 l(0, 0, 1);
  const auto t0 = std::chrono::steady_clock::now();
  const auto say = [&](double f) { reportProgress(progress, "multiple scattering", progressBase + progressSpan * f); };

  std::vector<glm::dvec3> xs(NS);
  for (int ir = 0; ir < nr; ++ir)
    for (int it = 0; it < nt; ++it) {
      const double r = radial.radius(ir), th = kPi * it / (nt - 1);
      xs[ir * nt + it] = r * glm::dvec3(std::sin(th), 0.0, std::cos(th));
    }

  // --- J2: once-scattered radiance on the fine grid, then the later phase function.
  std::vector<float> A(static_cast<std::size_t>(NS) * F);
  tbb::parallel_for(0, NS, [&](int s) {
    for (int f = 0; f < F; ++f) {
      const glm::dvec3 back = -sh.fine.direction(f);
      const double len = distanceToSphere(xs[s], back);
      A[static_cast<std::size_t>(s) * F + f] =
          static_cast<float>(sunlitRayIntegralFast(xs[s], back, l, sigma, len));
    }
  });
  std::vector<float> J(N, 0.0f);
  const auto gemm = [&](const std::vector<float>& in, int inCols, const std::vector<float>& Mt,
                        std::vector<float>& out) {
    // out[s][i] = Σ_j in[s][j] · Mt[j][i], rows in blocks of 4.
    tbb::parallel_for(0, (NS + 3) / 4, [&](int blk) {
      const int s0 = blk * 4, s1 = std::min(NS, s0 + 4);
      for (int s = s0; s < s1; ++s) std::fill_n(&out[static_cast<std::size_t>(s) * D], D, 0.0f);
      for (int j = 0; j < inCols; ++j) {
        const float* m = &Mt[static_cast<std::size_t>(j) * D];
        for (int s = s0; s < s1; ++s) {
          const float a = in[static_cast<std::size_t>(s) * inCols + j];
          if (a == 0.0f) continue;
          float* o = &out[static_cast<std::size_t>(s) * D];
          for (int i = 0; i < D; ++i) o[i] += a * m[i];
        }
      }
    });
  };
  gemm(A, F, sh.M2t, J);
  std::vector<float>().swap(A);
  const double tSource = seconds(t0);
  say(0.1);

  // --- Transport stencil: K points per (node, direction).
  const auto t1 = std::chrono::steady_clock::now();
  // Points per ray: the rule's panels may round the total up (at least 2 points each).
  std::vector<double> probeS, probeW;
  rayRule(sigma, 2.0, res.transportPoints, probeS, probeW);
  const int K = static_cast<int>(probeS.size());
  std::vector<StencilEntry> stencil(N * K);
  const std::size_t strideR = static_cast<std::size_t>(nt) * D, strideT = D;
  tbb::parallel_for(0, NS, [&](int s) {
    std::vector<double> ss, ww;
    const glm::dvec3 x = xs[s];
    for (int d = 0; d < D; ++d) {
      const int ia = d / nb;
      const glm::dvec3 w = sh.coarse.direction(d);
      const double len = distanceToSphere(x, -w);
      rayRule(sigma, len, res.transportPoints, ss, ww);
      const double wh = std::hypot(w.x, w.y);
      StencilEntry* e = &stencil[(static_cast<std::size_t>(s) * D + d) * K];
      for (int k = 0; k < K; ++k) {
        const glm::dvec3 y = x - ss[k] * w;
        const double rho = std::hypot(y.x, y.y);
        const double r = std::sqrt(rho * rho + y.z * y.z);
        int ir, it, ib;
        float wr[4];
        radial.cubic(r, ir, wr);
        const double th = std::atan2(rho, y.z);
        float wt[4];
        cubicWeights(th / kPi * (nt - 1), nt, it, wt);
        // Relative azimuth of the direction about l, folded to [0, π].
        double phi = 0.0;
        if (rho > 1e-12 && wh > 1e-12) {
          const double c = (w.x * y.x + w.y * y.y), sn = (w.y * y.x - w.x * y.y);
          phi = std::abs(std::atan2(sn, c));
        }
        double fbd;
        sh.coarse.locatePhi(phi, ib, fbd);
        e[k].base = static_cast<std::uint32_t>(ir * strideR + it * strideT + ia * nb + ib);
        for (int c = 0; c < 4; ++c) {
          e[k].wr[c] = static_cast<float>(ww[k]) * wr[c];
          e[k].wt[c] = wt[c];
        }
        e[k].fb = static_cast<float>(fbd);
      }
    }
  });
  const double tStencil = seconds(t1);
  say(0.2);

  std::vector<float> L(N);
  const auto transport = [&](const std::vector<float>& in, std::vector<float>& out) {
    tbb::parallel_for(0, NS, [&](int s) {
      for (int d = 0; d < D; ++d) {
        const std::size_t cell = static_cast<std::size_t>(s) * D + d;
        const StencilEntry* e = &stencil[cell * K];
        float acc = 0.0f;
        for (int k = 0; k < K; ++k) {
          const float* p = &in[e[k].base];
          const float fb = e[k].fb;
          for (int c = 0; c < 4; ++c, p += strideR) {
            const float* pt = p;
            float a = 0.0f;
            for (int t = 0; t < 4; ++t, pt += strideT) a += e[k].wt[t] * (pt[0] + fb * (pt[1] - pt[0]));
            acc += e[k].wr[c] * a;
          }
        }
        out[cell] = acc;
      }
    });
  };
  const auto applyK = [&](const std::vector<float>& in, std::vector<float>& out) {
    transport(in, L);
    gemm(L, D, sh.Mt, out);
  };

  // --- Orders.
  const auto t2 = std::chrono::steady_clock::now();
  const int orders = sh.settings.orders;
  std::vector<float> sum = J, next(N);
  int applications = 0;
  const int explicitOrders = orders > 0 ? orders : 18;
  for (int n = 3; n <= explicitOrders; ++n) {
    applyK(J, next);
    ++applications;
    J.swap(next);
    axpy(1.0f, J, sum);
    say(0.2 + 0.6 * (n - 2) / std::max(1, explicitOrders - 2) * (orders > 0 ? 1.0 : 0.3));
  }
  nlohmann::json sliceReport;
  std::vector<float> tail;
  if (orders <= 0) {
    // Remaining orders: the tail X = Σ_{n>N} J_n solves (I − K) X = K·J_N. Restarted GMRES,
    // right-preconditioned by an isotropic coarse-space correction: the slow modes of dense
    // particles are smooth, nearly isotropic diffusion modes, and the coarse operator
    // K_c = R·K·P (P: isotropic field on the spatial nodes, R: angular mean) holds them.
    // K_c is assembled from the transport stencil (the phase matrix conserves the angular
    // mean exactly), and B = I + P[(I − K_c)^{-1} − I]R.
    const auto& q = sh.coarse.nodeWeights();
    const double inv4pi = 1.0 / (4.0 * kPi);
    std::vector<double> Kc(static_cast<std::size_t>(NS) * NS, 0.0);
    tbb::parallel_for(0, NS, [&](int sIdx) {
      double* row = &Kc[static_cast<std::size_t>(sIdx) * NS];
      for (int dd = 0; dd < D; ++dd) {
        const StencilEntry* e = &stencil[(static_cast<std::size_t>(sIdx) * D + dd) * K];
        const double qd = q[dd] * inv4pi;
        for (int k = 0; k < K; ++k) {
          const std::size_t base = e[k].base;
          const int ir0 = static_cast<int>(base / strideR), it0 = static_cast<int>((base % strideR) / strideT);
          for (int c = 0; c < 4; ++c)
            for (int t = 0; t < 4; ++t) row[(ir0 + c) * nt + it0 + t] += qd * e[k].wr[c] * e[k].wt[t];
        }
      }
    });
    // LU of I − K_c with partial pivoting (serial: deterministic, NS³/3 flops).
    std::vector<double> LU(Kc.size());
    for (std::size_t i = 0; i < Kc.size(); ++i) LU[i] = -Kc[i];
    for (int i = 0; i < NS; ++i) LU[static_cast<std::size_t>(i) * NS + i] += 1.0;
    std::vector<int> piv(NS);
    for (int c = 0; c < NS; ++c) {
      int pr = c;
      for (int r2 = c + 1; r2 < NS; ++r2)
        if (std::abs(LU[static_cast<std::size_t>(r2) * NS + c]) > std::abs(LU[static_cast<std::size_t>(pr) * NS + c])) pr = r2;
      piv[c] = pr;
      if (pr != c)
        for (int j = 0; j < NS; ++j) std::swap(LU[static_cast<std::size_t>(c) * NS + j], LU[static_cast<std::size_t>(pr) * NS + j]);
      const double d = LU[static_cast<std::size_t>(c) * NS + c];
      if (d == 0.0) continue;
      for (int r2 = c + 1; r2 < NS; ++r2) {
        double& f = LU[static_cast<std::size_t>(r2) * NS + c];
        f /= d;
        if (f == 0.0) continue;
        const double* src = &LU[static_cast<std::size_t>(c) * NS];
        double* dst = &LU[static_cast<std::size_t>(r2) * NS];
        for (int j = c + 1; j < NS; ++j) dst[j] -= f * src[j];
      }
    }
    const auto coarseSolve = [&](std::vector<double>& x) {
      for (int c = 0; c < NS; ++c) std::swap(x[c], x[piv[c]]);
      for (int i = 0; i < NS; ++i)
        for (int j = 0; j < i; ++j) x[i] -= LU[static_cast<std::size_t>(i) * NS + j] * x[j];
      for (int i = NS - 1; i >= 0; --i) {
        for (int j = i + 1; j < NS; ++j) x[i] -= LU[static_cast<std::size_t>(i) * NS + j] * x[j];
        const double d = LU[static_cast<std::size_t>(i) * NS + i];
        x[i] = d != 0.0 ? x[i] / d : 0.0;
      }
    };
    const auto precondition = [&](const std::vector<float>& in, std::vector<float>& out) {
      std::vector<double> mean(NS, 0.0);
      tbb::parallel_for(0, NS, [&](int sIdx) {
        double m = 0.0;
        for (int dd = 0; dd < D; ++dd) m += q[dd] * in[static_cast<std::size_t>(sIdx) * D + dd];
        mean[sIdx] = m * inv4pi;
      });
      std::vector<double> corr = mean;
      coarseSolve(corr);
      tbb::parallel_for(0, NS, [&](int sIdx) {
        const float c = static_cast<float>(corr[sIdx] - mean[sIdx]);
        for (int dd = 0; dd < D; ++dd) {
          const std::size_t i = static_cast<std::size_t>(sIdx) * D + dd;
          out[i] = in[i] + c;
        }
      });
    };
    std::vector<float> b(N);
    applyK(J, b);
    ++applications;
    const int m = 24, maxApplications = 200;
    const double tol = 1e-4;
    std::vector<float> x(N, 0.0f), r = b, w(N), z(N);
    const double bnorm = std::sqrt(dot(b, b));
    double rnorm = bnorm;
    int iterations = 0;
    while (bnorm > 0.0 && rnorm > tol * bnorm && applications < maxApplications) {
      std::vector<std::vector<float>> V(1, r);
      const float inv = static_cast<float>(1.0 / rnorm);
      for (float& v : V[0]) v *= inv;
      std::vector<std::vector<double>> H(m + 1, std::vector<double>(m, 0.0));
      std::vector<double> cs(m), sn(m), g(m + 1, 0.0);
      g[0] = rnorm;
      int k = 0;
      for (; k < m && applications < maxApplications; ++k) {
        precondition(V[k], z);
        applyK(z, w);
        ++applications;
        ++iterations;
        // (I − K) z = z − K z
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N, 8192), [&](const auto& rg) {
          for (std::size_t i = rg.begin(); i < rg.end(); ++i) w[i] = z[i] - w[i];
        });
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
      // Solve the triangular system; x += B·(V y).
      std::vector<double> y(k, 0.0);
      for (int i = k - 1; i >= 0; --i) {
        double t = g[i];
        for (int j = i + 1; j < k; ++j) t -= H[i][j] * y[j];
        y[i] = H[i][i] != 0.0 ? t / H[i][i] : 0.0;
      }
      std::fill(z.begin(), z.end(), 0.0f);
      for (int j = 0; j < k; ++j) axpy(static_cast<float>(y[j]), V[j], z);
      precondition(z, w);
      axpy(1.0f, w, x);
      // True residual r = b − (I − K) x.
      applyK(x, w);
      ++applications;
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, N, 8192), [&](const auto& rg) {
        for (std::size_t i = rg.begin(); i < rg.end(); ++i) r[i] = b[i] - x[i] + w[i];
      });
      rnorm = std::sqrt(dot(r, r));
      say(0.35 + 0.45 * std::min(1.0, static_cast<double>(applications) / maxApplications));
    }
    tail = std::move(x);
    sliceReport["gmres_iterations"] = iterations;
    sliceReport["gmres_relative_residual"] = bnorm > 0 ? rnorm / bnorm : 0.0;
  }
  const double tIterate = seconds(t2);
  say(0.8);

  // --- Gather to the table nodes: LM(S, v) = ∫ σ e^{−σt} ΣJ(S + t v, −v) dt, stored as its
  // mean source LM / (1 − e^{−σ·chord}) (cloudlut_shading.glsl); on a grazing chord the mean
  // source is the source at S.
  const auto t3 = std::chrono::steady_clock::now();
  const auto& ax = table.axes();
  const int nS = ax[0].size, nP = ax[1].size, nV = ax[2].size;
  const auto gather = [&](const std::vector<float>& field, Table4D& dst) {
  tbb::parallel_for(0, nS * nP, [&](int row) {
    const int iS = row % nS, iP = row / nS;
    const double thS = ax[0].value(iS), phV = ax[1].value(iP);
    const glm::dvec3 S(std::sin(thS), 0.0, std::cos(thS));
    const glm::dvec3 fx(std::cos(thS), 0.0, -std::sin(thS)), fy(0.0, 1.0, 0.0);
    std::vector<double> ss, ww;
    for (int iV = 0; iV < nV; ++iV) {
      const double thV = ax[2].value(iV);
      const glm::dvec3 v = std::sin(thV) * (std::cos(phV) * fx + std::sin(phV) * fy) - std::cos(thV) * S;
      const double chord = std::max(0.0, -2.0 * glm::dot(S, v));
      double opacity = -std::expm1(-sigma * chord);
      if (opacity > 1e-9) {
        rayRule(sigma, chord, res.gatherPoints, ss, ww);
      } else {
        ss.assign(1, 0.0);
        ww.assign(1, 1.0);
        opacity = 1.0;
      }
      const glm::dvec3 w = -v;
      int ia;
      double fad;
      sh.coarse.locateTheta(std::acos(std::clamp(w.z, -1.0, 1.0)), ia, fad);
      const float fa = static_cast<float>(fad);
      const double wh = std::hypot(w.x, w.y);
      double value = 0.0;
      for (std::size_t k = 0; k < ss.size(); ++k) {
        const glm::dvec3 y = S + ss[k] * v;
        const double rho = std::hypot(y.x, y.y);
        const double r = std::sqrt(rho * rho + y.z * y.z);
        int ir, it, ib;
        float wr[4];
        radial.cubic(r, ir, wr);
        float wt[4];
        cubicWeights(std::atan2(rho, y.z) / kPi * (nt - 1), nt, it, wt);
        double phi = 0.0;
        if (rho > 1e-12 && wh > 1e-12)
          phi = std::abs(std::atan2(w.y * y.x - w.x * y.y, w.x * y.x + w.y * y.y));
        double fbd;
        sh.coarse.locatePhi(phi, ib, fbd);
        const float fb = static_cast<float>(fbd);
        float corner[2] = {0.0f, 0.0f};
        for (int c = 0; c < 2; ++c) {
          const float* p = &field[ir * strideR + it * strideT + (ia + c) * nb + ib];
          for (int j = 0; j < 4; ++j, p += strideR) {
            const float* pt = p;
            float a = 0.0f;
            for (int t = 0; t < 4; ++t, pt += strideT) a += wt[t] * (pt[0] + fb * (pt[1] - pt[0]));
            corner[c] += wr[j] * a;
          }
        }
        value += ww[k] * (corner[0] + fa * (corner[1] - corner[0]));
      }
      dst.at(dst.index(iS, iP, iV, slice), 0) = static_cast<float>(std::max(0.0, value / opacity));
    }
  });
  };
  if (!tail.empty() && !tailTable) axpy(1.0f, tail, sum);  // no closure requested: plain sum
  gather(sum, table);
  if (tailTable && !tail.empty()) gather(tail, *tailTable);
  const double tGather = seconds(t3);
  say(1.0);

  sliceReport["sigma"] = sigma;
  sliceReport["orders"] = orders > 0 ? nlohmann::json(orders) : nlohmann::json("converged");
  sliceReport["operator_applications"] = applications;
  sliceReport["seconds"] = {{"first_scattering_source", tSource},
                            {"transport_stencil", tStencil},
                            {"orders", tIterate},
                            {"gather", tGather}};
  report = sliceReport;
}

}  // namespace cloudlut::bake
