// bake/PhaseResolution: the expected error that a direction grid's hat functions cause in the
// transport asymmetry 1 − g of a phase function, checked against computations that share no
// code with it: Henyey–Greenstein's Legendre moments (g^l, analytic), the closed-form
// asymmetries of HG and Cornette–Shanks, and the error the fast method's own phase matrix
// (DirectionGrid.h) makes on its direction grids; plus the `bake` warning end to end.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include <glm/geometric.hpp>

#include "support/CliRunner.h"
#include "bake/DirectionGrid.h"
#include "bake/PhaseResolution.h"
#include "core/Glsl.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

// Transport asymmetry of HG(g) as a grid of uniform spacing π/K sees it, from the Legendre
// expansion P(μ) = Σ (2l+1) g^l P_l(μ) / 4π: g_grid = ∫ P Icos dΩ = ½ Σ (2l+1) g^l ∫ Icos P_l dμ,
// Icos the piecewise-linear interpolant of cos θ on the nodes θ_k = kπ/K (dimensionless).
// The integrals over θ by composite Simpson, fine enough for the highest P_l kept.
double hgGridAsymmetryFromLegendre(double g, int K) {
  const int lMax = static_cast<int>(std::ceil(std::log(1e-13) / std::log(g)));
  const int n = 2 * 40000;  // Simpson intervals over [0, π]
  std::vector<double> moments(lMax + 1, 0.0);
  std::vector<double> P(lMax + 1);
  for (int i = 0; i <= n; ++i) {
    const double theta = kPi * i / n;
    const double mu = std::cos(theta);
    const double h = kPi / K;
    const int k = std::min(K - 1, static_cast<int>(theta / h));
    const double f = (theta - k * h) / h;
    const double icos = (1.0 - f) * std::cos(k * h) + f * std::cos((k + 1) * h);
    const double w = (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * (kPi / n) / 3.0 * std::sin(theta);
    P[0] = 1.0;
    if (lMax >= 1) P[1] = mu;
    for (int l = 2; l <= lMax; ++l) P[l] = ((2.0 * l - 1.0) * mu * P[l - 1] - (l - 1.0) * P[l - 2]) / l;
    for (int l = 0; l <= lMax; ++l) moments[l] += w * icos * P[l];
  }
  double sum = 0.0, gl = 1.0;
  for (int l = 0; l <= lMax; ++l, gl *= g) sum += 0.5 * (2.0 * l + 1.0) * gl * moments[l];
  return sum;
}

}  // namespace

TEST_CASE("phase resolution: exact asymmetries match the closed forms", "[phase]") {
  for (float g : {0.3f, 0.7f, 0.9f, 0.99f}) {
    INFO("g = " << g);
    const double gd = g;  // the phase is evaluated with this float g
    CHECK(bake::estimatePhaseResolution({PhaseKind::HenyeyGreenstein, g}, 5.0 * kDeg).asymmetry == Approx(gd).epsilon(2e-5));
    const double cs = 3.0 * gd * (4.0 + gd * gd) / (5.0 * (2.0 + gd * gd));
    CHECK(bake::estimatePhaseResolution({PhaseKind::CornetteShanks, g}, 5.0 * kDeg).asymmetry == Approx(cs).epsilon(2e-5));
  }
  CHECK(std::fabs(bake::estimatePhaseResolution({PhaseKind::Isotropic, 0.0f}, 5.0 * kDeg).asymmetry) < 1e-6);
}

TEST_CASE("phase resolution: HG's grid asymmetry agrees with its Legendre moments", "[phase]") {
  for (float g : {0.7f, 0.9f})
    for (int K : {12, 24, 60}) {
      INFO("g = " << g << ", spacing pi/" << K);
      const bake::PhaseResolutionEstimate e = bake::estimatePhaseResolution({PhaseKind::HenyeyGreenstein, g}, kPi / K);
      const double legendre = hgGridAsymmetryFromLegendre(g, K);
      CHECK(e.gridAsymmetry == Approx(legendre).margin(2e-6));
      const double eps = std::fabs(legendre - g) / (1.0 - g);
      CHECK(e.relativeError == Approx(eps).epsilon(0.01).margin(1e-5));
    }
}

TEST_CASE("phase resolution: the error vanishes on fine grids and grows as the grid coarsens", "[phase]") {
  const Phase phases[] = {{PhaseKind::HenyeyGreenstein, 0.7f}, {PhaseKind::HenyeyGreenstein, 0.9f}, {PhaseKind::CornetteShanks, 0.7f},
                          {PhaseKind::CornetteShanks, 0.9f}, {PhaseKind::JendersieDeon, 10.0f}, {PhaseKind::JendersieDeon, 30.0f}};
  for (const auto& p : phases) {
    INFO(describePhase(p));
    CHECK(bake::estimatePhaseResolution(p, 0.25 * kDeg).relativeError < 1e-3);
    double previous = 0.0;
    for (double deg : {0.5, 1.0, 2.0, 4.0, 8.0, 16.0}) {
      const double e = bake::estimatePhaseResolution(p, deg * kDeg).relativeError;
      CHECK(e > previous);
      previous = e;
    }
    // Smooth phase functions follow ε ≈ g Δ² / (12 (1 − g)); the sharp jd peak stays within 2×.
    const double d = kPi / 45.0;  // 4°
    const auto e = bake::estimatePhaseResolution(p, d);
    const double smooth = e.asymmetry * d * d / (12.0 * (1.0 - e.asymmetry));
    CHECK(e.relativeError > 0.5 * smooth);
    CHECK(e.relativeError < 2.0 * smooth);
  }
}

namespace {

// The relative error in 1 − g (dimensionless, signed: negative = broadened) that the fast
// method's phase matrix makes on a folded DirectionGrid, averaged over its nodes with their
// quadrature weights. Column j of the matrix scatters the mirror-symmetric hat of node j (half
// its mass about ω_j, half about the mirror image ω_j'); the output's first moment about ω_j
// is then g_j (1 + ω_j·ω_j') / 2 per unit mass, so g_j is read off the nodes near the mirror
// plane (ω_j·ω_j' > 1/2), where that division is well conditioned.
double phaseMatrixError(int thetaNodes, int phiNodes, const Phase& p, double g) {
  const bake::DirectionGrid grid(thetaNodes, phiNodes, 1.0);
  const auto M = bake::phaseMatrix(grid, [&](double mu) {
    return static_cast<double>(phaseValue(p, static_cast<float>(mu)));
  });
  const int n = grid.count();
  const auto& q = grid.nodeWeights();
  const auto mirror = [](glm::dvec3 w) { return glm::dvec3(w.x, -w.y, w.z); };
  double sum = 0.0, weight = 0.0;
  for (int j = 0; j < n; ++j) {
    const glm::dvec3 wj = grid.direction(j);
    const double c = glm::dot(wj, mirror(wj));
    if (c < 0.5) continue;
    double moment = 0.0, mass = 0.0;
    for (int i = 0; i < n; ++i) {
      const glm::dvec3 wi = grid.direction(i);
      const double m = q[i] * M[static_cast<std::size_t>(i) * n + j];
      moment += m * 0.5 * (glm::dot(wi, wj) + glm::dot(mirror(wi), wj));
      mass += m;
    }
    const double gj = moment / mass * 2.0 / (1.0 + c);
    sum += q[j] * (gj - g) / (1.0 - g);
    weight += q[j];
  }
  return sum / weight;
}

}  // namespace

TEST_CASE("phase resolution: the estimate tracks the fast method's own phase matrix", "[phase]") {
  // The estimate at a grid's coarsest spacing against the error the real operator makes:
  // same sign (the hats broaden the phase), and larger by at most half (measured: ~25%).
  const Phase phases[] = {{PhaseKind::HenyeyGreenstein, 0.7f}, {PhaseKind::CornetteShanks, 0.7f}, {PhaseKind::CornetteShanks, 0.9f},
                          {PhaseKind::JendersieDeon, 10.0f}};
  for (auto nodes : {std::array<int, 2>{24, 13}, std::array<int, 2>{48, 25}})
    for (const auto& p : phases) {
      INFO(nodes[0] << "x" << nodes[1] << " grid, " << describePhase(p));
      const double spacing = std::max(kPi / (nodes[0] - 1), kPi / (nodes[1] - 1));
      const auto e = bake::estimatePhaseResolution(p, spacing);
      const double op = phaseMatrixError(nodes[0], nodes[1], p, e.asymmetry);
      CHECK(e.gridAsymmetry < e.asymmetry);
      CHECK(op < 0.0);
      CHECK(e.relativeError >= -op);
      CHECK(e.relativeError <= -1.5 * op);
    }
}

TEST_CASE("phase resolution: jd at 10 um is flagged on the fast method's grid, iso never", "[phase]") {
  bake::ScatteringSettings s;
  s.firstPhase = s.laterPhase = {PhaseKind::JendersieDeon, 10.0f};
  const auto checks = bake::checkPhaseResolution(s);
  REQUIRE(!checks.empty());
  const auto& c = checks.front();
  CHECK(c.which == "later");
  CHECK(c.estimate.relativeError > bake::kPhaseResolutionTolerance);
  CHECK(c.estimate.peakValue == Approx(586.0).epsilon(0.01));  // the published fit's forward peak at 10 µm (tests/test_parameterization.cpp)
  CHECK(c.estimate.peakHalfWidth > 0.2 * kDeg);
  CHECK(c.estimate.peakHalfWidth < 1.0 * kDeg);
  // The advised spacing meets the tolerance and a coarser one would not.
  CHECK(c.neededSpacing < c.spacing);
  CHECK(bake::estimatePhaseResolution(c.phase, c.neededSpacing).relativeError <= bake::kPhaseResolutionTolerance);
  CHECK(bake::estimatePhaseResolution(c.phase, 1.1 * c.neededSpacing).relativeError > bake::kPhaseResolutionTolerance);

  s.multiple = false;  // L1 holds no phase function
  CHECK(bake::checkPhaseResolution(s).empty());

  s.multiple = true;
  s.firstPhase = s.laterPhase = {PhaseKind::Isotropic, 0.0f};
  for (auto method : {bake::ScatteringMethod::Fast, bake::ScatteringMethod::Paper})
    for (auto dims : {std::array<int, 4>{32, 64, 16, 8}, std::array<int, 4>{4, 5, 2, 2}}) {
      s.method = method;
      s.dims = dims;
      CHECK(bake::checkPhaseResolution(s, 1e-6).empty());
    }
  for (double deg : {0.5, 5.0, 15.0, 45.0, 90.0}) {
    const auto e = bake::estimatePhaseResolution({PhaseKind::Isotropic, 0.0f}, deg * kDeg);
    CHECK(e.relativeError < 1e-6);
    CHECK(e.peakHalfWidth == Approx(kPi));  // no peak
  }
}

TEST_CASE("bake warns, once and with the expected error, when the phase is too sharp for the grid", "[cli][phase]") {
  TempDir tmp;
  const std::string common = " --tables multiple --res-sc 8,16,6,2 --densities -1,0 --orders 2 --format bin --quiet --out '";
  const CliResult jd = runCli("bake --phase jd --droplet-um 10" + common + (tmp / "jd").string() + "'");
  CHECK(jd.exitCode == 0);
  CHECK(std::count(jd.err.begin(), jd.err.end(), '\n') == 1);
  CHECK(jd.err.find("warning") != std::string::npos);
  CHECK(jd.err.find("jd d=10 um") != std::string::npos);
  CHECK(jd.err.find("expected error") != std::string::npos);
  CHECK(std::filesystem::exists(tmp / "jd" / "manifest.json"));

  const CliResult iso = runCli("bake --phase iso" + common + (tmp / "iso").string() + "'");
  CHECK(iso.exitCode == 0);
  CHECK(iso.err.empty());

  // The default phase functions (cs 0.9, then 0.7) on the default grid: no warning.
  const CliResult cs = runCli("bake" + common + (tmp / "cs").string() + "'");
  CHECK(cs.exitCode == 0);
  CHECK(cs.err.empty());

  const CliResult single = runCli("bake --phase jd --tables single --res-sc 8,16,6,2 --densities -1,0 --format bin --quiet --out '" +
                                  (tmp / "single").string() + "'");
  CHECK(single.exitCode == 0);
  CHECK(single.err.empty());
}
