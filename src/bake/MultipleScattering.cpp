#include "bake/MultipleScattering.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include "bake/DirectionGrid.h"
#include "bake/ParallelVectors.h"
#include "bake/Quadrature.h"
#include "bake/ScatteringOperator.h"
#include "bake/SphereField.h"
#include "bake/TailSolver.h"
#include "core/Glsl.h"

namespace cloudlut::bake {

struct FastMultipleScattering::Shared {
  ScatteringSettings settings;
  FastResolution res;
  DirectionGrid coarse, fine;  // J_2's directions (D) and the once-scattered light's (F)
  std::vector<float> Mt;   // D × D: Mt[j·D + i] = M[i][j], the later phase matrix
  std::vector<float> M2t;  // F × D: M2t[f·D + i] = M2[i][f], the second scattering of sunlight
  mutable TransportStencil::Storage stencils;  // reused by the density slices (thread-safe)
};

namespace {

// Relative field total of an order below which the order loop stops (see bakeSlice).
constexpr double kOrderTolerance = 1e-5;

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::function<double(double)> phaseOf(const Phase& p) {
  return [p](double mu) { return static_cast<double>(phaseValue(p, static_cast<float>(mu))); };
}

// The row-major rows × cols matrix A as float, transposed: At[j·rows + i] = A[i·cols + j].
std::vector<float> transposedFloat(const std::vector<double>& A, int rows, int cols) {
  std::vector<float> At(static_cast<std::size_t>(rows) * cols);
  for (int i = 0; i < rows; ++i)
    for (int j = 0; j < cols; ++j)
      At[static_cast<std::size_t>(j) * rows + i] = static_cast<float>(A[static_cast<std::size_t>(i) * cols + j]);
  return At;
}

// J_2(x, ω) = ∫ p_later(ω·ω') p_first(−l·ω') A(x, ω') dω' at every node and direction, with
// A(x, ω') = ∫_0^{d(x, −ω')} σ e^{−σs} e^{−σ d_sun(x − sω')} ds the once-scattered light (phase
// excluded) arriving at x from ω' (sunlitRayIntegralFast): A on the fine grid refined toward
// the sun's forward peak, then one product with the second-scattering matrix.
std::vector<float> firstScatteringSource(const SphereField& field, const DirectionGrid& fine,
                                         const std::vector<float>& M2t, double sigma) {
  const int NS = field.nodeCount(), F = fine.count(), nt = field.zenithCount();
  const glm::dvec3 l(0, 0, 1);
  std::vector<float> A(static_cast<std::size_t>(NS) * F);  // in the field's layout with F directions
  tbb::parallel_for(0, NS, [&](int s) {
    const glm::dvec3 x = field.node(s);
    const std::size_t first = static_cast<std::size_t>(s / nt) * F * nt + static_cast<std::size_t>(s % nt);
    for (int f = 0; f < F; ++f) {
      const glm::dvec3 back = -fine.direction(f);
      A[first + static_cast<std::size_t>(f) * nt] =
          static_cast<float>(sunlitRayIntegralFast(x, back, l, sigma, distanceToSphere(x, back)));
    }
  });
  std::vector<float> J(field.size(), 0.0f);
  convolvePhase(A, F, M2t, field.directionCount(), field, J);
  return J;
}

// J(y, w) read through the stencil p = field.locate(y, w, ·) at the direction-zenith node ia of
// w and the fraction fa toward ia + 1: linear between the two zenith nodes.
float sampleField(const SphereField& field, const std::vector<float>& J, const FieldPoint& p, int ia, float fa) {
  const std::size_t strideR = field.radialStride(), strideB = field.directionStride();
  const std::size_t zenithOffset = static_cast<std::size_t>(field.directions().phiCount()) * strideB;
  float corner[2];  // the two direction-zenith nodes about w
  for (int c = 0; c < 2; ++c)
    corner[c] = sumFloat4(interpolateFieldTerms(&J[p.offset + static_cast<std::size_t>(ia + c) * zenithOffset],
                                                strideR, strideB, p.wr, p.wt, p.fb));
  return corner[0] + fa * (corner[1] - corner[0]);
}

// The field J given on `from`, interpolated at every node and direction of `to` (sampleField):
// J_to(x_s, ω_d) = J_from(x_s, ω_d).
std::vector<float> interpolateField(const SphereField& from, const std::vector<float>& J, const SphereField& to) {
  const DirectionGrid& dirs = to.directions();
  std::vector<float> out(to.size());
  tbb::parallel_for(0, dirs.count(), [&](int d) {
    const glm::dvec3 w = dirs.direction(d);
    int ia;
    double fa;
    from.directions().locateTheta(std::acos(std::clamp(w.z, -1.0, 1.0)), ia, fa);
    const double wh = std::hypot(w.x, w.y);
    // eight nodes at a time (locatePoints8: locate's values)
    for (int s0 = 0; s0 < to.nodeCount(); s0 += 8) {
      const int n = std::min(8, to.nodeCount() - s0);
      glm::dvec3 y[8];
      FieldPoint p[8];
      for (int k = 0; k < n; ++k) y[k] = to.node(s0 + k);
      from.locatePoints8(y, w, wh, n, p);
      for (int k = 0; k < n; ++k)
        out[to.index(s0 + k, d)] = sampleField(from, J, p[k], ia, static_cast<float>(fa));
    }
  });
  return out;
}

// The table's mean source at its nodes of slice `slice`: with LM(S, v) = ∫_0^chord σ e^{−σt}
// J(S + t v, −v) dt (J read at the direction zenith of −v, linear between its two nodes), the
// stored value is LM / (1 − e^{−σ·chord}) (cloudlut_shading.glsl); on a grazing chord the mean
// source is the source at S.
void gatherTable(const SphereField& field, const std::vector<float>& J, double sigma, int points, int slice,
                 Table4D& dst) {
  const auto& ax = dst.axes();
  const int nS = ax[0].size, nP = ax[1].size, nV = ax[2].size;
  const DirectionGrid& dirs = field.directions();
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
        attenuatedRayRule(sigma, chord, points, ss, ww);
      } else {
        ss.assign(1, 0.0);
        ww.assign(1, 1.0);
        opacity = 1.0;
      }
      const glm::dvec3 w = -v;
      int ia;
      double fad;
      dirs.locateTheta(std::acos(std::clamp(w.z, -1.0, 1.0)), ia, fad);
      const float fa = static_cast<float>(fad);
      const double wh = std::hypot(w.x, w.y);
      // The points S + s_k v = S − s_k w located eight at a time along the ray.
      double value = 0.0;
      FieldPoint located[8];
      const std::size_t n = ss.size();
      for (std::size_t k = 0; k < n; ++k) {
        if (k % 8 == 0)
          field.locateRay8(S, w, wh, &ss[k], static_cast<int>(std::min<std::size_t>(8, n - k)), located);
        value += ww[k] * sampleField(field, J, located[k % 8], ia, fa);
      }
      dst.at(dst.index(iS, iP, iV, slice), 0) = static_cast<float>(std::max(0.0, value / opacity));
    }
  });
}

}  // namespace

FastMultipleScattering::FastMultipleScattering(const ScatteringSettings& settings, const FastResolution& res) {
  auto sh = std::make_unique<Shared>();
  sh->settings = settings;
  sh->res = res;
  sh->coarse = DirectionGrid(res.dirTheta, res.dirPhi, 1.0);
  sh->fine = DirectionGrid(res.fineTheta, res.finePhi, 2.0);
  const auto later = phaseOf(settings.laterPhase), first = phaseOf(settings.firstPhase);
  const int D = sh->coarse.count(), F = sh->fine.count();
  sh->Mt = transposedFloat(phaseMatrix(sh->coarse, later), D, D);
  sh->M2t = transposedFloat(secondScatteringMatrix(sh->coarse, sh->fine, first, later), D, F);
  // Every stencil array as large as the largest stencil (either grid, either rule): the pool
  // then holds one array per slice running at once, not one per size (RecycledArrays.h).
  const std::size_t cells = static_cast<std::size_t>(D) * static_cast<std::size_t>(
                                std::max(res.radial * res.zenith, res.thinRadial * res.thinZenith));
  const int points = std::max(TransportStencil::pointsPerRay(1.0, res.transportPoints),
                              TransportStencil::pointsPerRay(kFarPanelMaxSigma, res.denseTransportPoints));
  sh->stencils.setMinimumSize(cells * static_cast<std::size_t>(points));
  shared_ = std::move(sh);
}

FastMultipleScattering::~FastMultipleScattering() = default;

void FastMultipleScattering::bakeSlice(double sigma, int slice, Table4D& table, Table4D* tailTable,
                                       nlohmann::json& report, const ProgressFn& progress, double progressBase,
                                       double progressSpan) const {
  const Shared& sh = *shared_;
  const FastResolution& res = sh.res;
  const auto say = [&](double f) { reportProgress(progress, "multiple scattering", progressBase + progressSpan * f); };
  const SphereField field(res.radial, res.zenith, res.grading, res.linearShare, sigma, sh.coarse);
  // The grid of orders 3 … ∞: `field` itself, or a coarser one for a thin particle.
  const bool thin = sigma <= res.thinSigma;
  std::unique_ptr<const SphereField> thinField;
  if (thin)
    thinField = std::make_unique<const SphereField>(res.thinRadial, res.thinZenith, res.grading, res.linearShare,
                                                    sigma, sh.coarse);
  const SphereField& later = thin ? *thinField : field;

  // J_2: the first scattering of sunlight, scattered once more.
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<float> J = firstScatteringSource(field, sh.fine, sh.M2t, sigma);
  std::vector<float> J2;  // kept on its own grid when the later orders run on another
  if (thin) {
    J2 = std::move(J);
    J = interpolateField(field, J2, later);
  }
  const double tSource = seconds(t0);
  say(0.1);

  // K = M·T, its transport stencil built once for every order of this density.
  const auto t1 = std::chrono::steady_clock::now();
  const TransportStencil transport(later, sigma,
                                   sigma >= kFarPanelMaxSigma ? res.denseTransportPoints : res.transportPoints, sh.stencils);
  ScatteringOperator K(transport, sh.Mt, later);
  const double tStencil = seconds(t1);
  say(0.2);

  // Orders 3 … N: J_{n+1} = K·J_n, summed from J_2 on (from J_3 on when J_2 stays on its own
  // grid). The loop stops early once an order's field total Σ J_n (over every node and
  // direction, J ≥ 0) falls below kOrderTolerance · Σ (J_2 + … + J_n): the orders decay
  // geometrically (ratio q < 1, small in thin particles), so the truncated rest is below
  // kOrderTolerance · q/(1 − q) of the sum.
  const auto t2 = std::chrono::steady_clock::now();
  const int orders = sh.settings.orders;
  std::vector<float> sum = thin ? std::vector<float>(later.size(), 0.0f) : J, next(later.size());
  int applications = 0, lastOrder = 2;
  const int explicitOrders = orders > 0 ? orders : 18;
  double sumTotal = total(J);
  bool negligible = false;
  for (int n = 3; n <= explicitOrders && !negligible; ++n) {
    K.apply(J, next);
    ++applications;
    J.swap(next);
    axpy(1.0f, J, sum);
    lastOrder = n;
    const double orderTotal = total(J);
    sumTotal += orderTotal;
    negligible = !(orderTotal > kOrderTolerance * sumTotal);
    say(0.2 + 0.6 * (n - 2) / std::max(1, explicitOrders - 2) * (orders > 0 ? 1.0 : 0.3));
  }
  nlohmann::json sliceReport;
  sliceReport["last_order_computed"] = lastOrder;
  std::vector<float> tail;
  if (orders <= 0 && !negligible) {  // a negligible order leaves a negligible tail
    // Orders N+1 … ∞: (I − K) X = K·J_N (TailSolver.h).
    const CoarseCorrection B(later, transport.isotropicCoarseOperator());
    std::vector<float> b(later.size());
    K.apply(J, b);
    ++applications;
    TailSolution sol = solveTail(K, B, b, TailSettings{}, applications, [&](double f) { say(0.35 + 0.45 * f); });
    tail = std::move(sol.x);
    sliceReport["gmres_iterations"] = sol.iterations;
    sliceReport["gmres_relative_residual"] = sol.relativeResidual;
  }
  const double tIterate = seconds(t2);
  say(0.8);

  // Gather to the table nodes (the tail to its own table when the baker closes it on energy),
  // from the grid of J_2: a thin particle's later orders are interpolated onto it first.
  const auto t3 = std::chrono::steady_clock::now();
  if (!tail.empty() && !tailTable) axpy(1.0f, tail, sum);  // no closure requested: plain sum
  if (thin) {
    sum = interpolateField(later, sum, field);
    axpy(1.0f, J2, sum);
    if (!tail.empty()) tail = interpolateField(later, tail, field);
  }
  gatherTable(field, sum, sigma, res.gatherPoints, slice, table);
  if (tailTable && !tail.empty()) gatherTable(field, tail, sigma, res.gatherPoints, slice, *tailTable);
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
