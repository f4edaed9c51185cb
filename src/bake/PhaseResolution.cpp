#include "bake/PhaseResolution.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bake/MultipleScattering.h"
#include "bake/Quadrature.h"
#include "core/Glsl.h"

namespace cloudlut::bake {

namespace {

constexpr double kPi = 3.14159265358979323846;

// P(cos θ), sr⁻¹.
double phaseAt(const Phase& p, double theta) {
  return phaseValue(p, static_cast<float>(std::cos(theta)));
}

// Over one interval [a, b] between adjacent nodes: the phase's mass that the hat functions of
// the two nodes take, ∫_a^b P(cos θ) h(θ) dΩ with h = (b − θ)/(b − a) for `left` and
// (θ − a)/(b − a) for `right` (dimensionless), and the exact first moment ∫_a^b P μ dΩ.
// Composite 8-point Gauss–Legendre; an interval starting at θ = 0 is graded as θ = b ξ³ (the
// forward peak sits there), the others are split into uniform panels.
void intervalMoments(const Phase& p, double a, double b, double& left, double& right, double& moment) {
  const GaussRule& g = gaussLegendre(8);
  left = right = moment = 0.0;
  const bool graded = a == 0.0;
  const int panels = graded ? 256 : 32;
  for (int c = 0; c < panels; ++c)
    for (int k = 0; k < 8; ++k) {
      const double xi = (c + g.x[k]) / panels;
      double theta, jac;
      if (graded) {
        theta = b * xi * xi * xi;
        jac = 3.0 * b * xi * xi;
      } else {
        theta = a + (b - a) * xi;
        jac = b - a;
      }
      const double w = g.w[k] / panels * jac * 2.0 * kPi * std::sin(theta) * phaseAt(p, theta);
      const double f = (theta - a) / (b - a);
      left += w * (1.0 - f);
      right += w * f;
      moment += w * std::cos(theta);
    }
}

std::vector<double> uniformNodes(double spacing) {
  if (!(spacing > 0.0)) throw std::invalid_argument("phase resolution: the spacing must be positive");
  const int K = std::max(1, static_cast<int>(std::ceil(kPi / std::min(spacing, kPi) - 1e-9)));
  std::vector<double> nodes(K + 1);
  for (int k = 0; k <= K; ++k) nodes[k] = kPi * k / K;
  return nodes;
}

double uniformSpacing(double spacing) { return kPi / (static_cast<double>(uniformNodes(spacing).size()) - 1.0); }

}  // namespace

double phasePeakHalfWidth(const Phase& phase) {
  const double half = 0.5 * phaseAt(phase, 0.0);
  // First crossing on a grid geometric in θ (peaks span 1e-4 … 1 rad), then bisection.
  double lo = 0.0, hi = -1.0;
  for (double t = 1e-5; t < kPi; t *= 1.05) {
    if (phaseAt(phase, t) <= half) {
      hi = t;
      break;
    }
    lo = t;
  }
  if (hi < 0.0) return kPi;  // never falls to half: no peak
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (phaseAt(phase, mid) <= half ? hi : lo) = mid;
  }
  return hi;
}

PhaseResolutionEstimate estimatePhaseResolution(const Phase& phase, const std::vector<double>& nodes) {
  if (nodes.size() < 2 || nodes.front() != 0.0 || std::fabs(nodes.back() - kPi) > 1e-9)
    throw std::invalid_argument("phase resolution: nodes must run from 0 to pi");
  for (std::size_t k = 1; k < nodes.size(); ++k)
    if (!(nodes[k] > nodes[k - 1])) throw std::invalid_argument("phase resolution: nodes must ascend");
  const std::size_t n = nodes.size();
  std::vector<double> m(n, 0.0);  // m_k = ∫ P hat_k dΩ
  double exact = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    double left, right, mu;
    intervalMoments(phase, nodes[k], nodes[k + 1], left, right, mu);
    m[k] += left;
    m[k + 1] += right;
    exact += mu;
  }
  double mass = 0.0, grid = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    mass += m[k];
    grid += m[k] * std::cos(nodes[k]);
  }
  PhaseResolutionEstimate e;
  e.asymmetry = exact / mass;
  e.gridAsymmetry = grid / mass;
  e.relativeError = std::fabs(e.gridAsymmetry - e.asymmetry) / (1.0 - e.asymmetry);
  e.peakValue = phaseAt(phase, 0.0);
  e.peakHalfWidth = phasePeakHalfWidth(phase);
  return e;
}

PhaseResolutionEstimate estimatePhaseResolution(const Phase& phase, double spacing) {
  return estimatePhaseResolution(phase, uniformNodes(spacing));
}

double spacingForError(const Phase& phase, double tolerance) {
  constexpr int kMax = 8192;
  const auto ok = [&](int K) { return estimatePhaseResolution(phase, kPi / K).relativeError <= tolerance; };
  // Grow K geometrically to the first K that meets the tolerance, then bisect below it.
  int bad = 0, good = 6;
  while (!ok(good)) {
    bad = good;
    if (good >= kMax) return kPi / kMax;
    good = std::min(kMax, good * 3 / 2 + 1);
  }
  while (good - bad > 1) {
    const int mid = (good + bad) / 2;
    (ok(mid) ? good : bad) = mid;
  }
  return kPi / good;
}

namespace {

// Nodes of the fast method's once-scattered grid in scattering angle from the sun's forward
// direction (radians): π (j/(n − 1))², j = 0 … n − 1.
std::vector<double> sunGradedNodes(int n) {
  std::vector<double> nodes(n);
  for (int j = 0; j < n; ++j) {
    const double x = static_cast<double>(j) / (n - 1);
    nodes[j] = kPi * x * x;
  }
  nodes.back() = kPi;
  return nodes;
}

// Nodes over [0, span] (radians) for a spacing of at most `spacing`: ceil(span/spacing) + 1.
int nodesFor(double span, double spacing) { return static_cast<int>(std::ceil(span / spacing - 1e-9)) + 1; }

}  // namespace

std::vector<PhaseResolutionCheck> checkPhaseResolution(const ScatteringSettings& settings, double tolerance) {
  std::vector<PhaseResolutionCheck> checks;
  if (!settings.multiple) return checks;
  const auto uniform = [&](const std::string& grid, const char* which, const Phase& phase, double spacing,
                           const auto& advise) {
    if (phase.kind == PhaseKind::Isotropic) return;
    const PhaseResolutionEstimate e = estimatePhaseResolution(phase, spacing);
    if (e.relativeError <= tolerance) return;
    const double needed = spacingForError(phase, tolerance);
    checks.push_back({grid, which, phase, uniformSpacing(spacing), e, needed, advise(needed)});
  };
  if (settings.method == ScatteringMethod::Fast) {
    const FastResolution res;
    const double coarse = std::max(kPi / (res.dirTheta - 1), kPi / (res.dirPhi - 1));
    uniform("the fast method's " + std::to_string(res.dirTheta) + "x" + std::to_string(res.dirPhi) + " direction grid",
            "later", settings.laterPhase, coarse, [&](double needed) {
              const int n = nodesFor(kPi, needed);
              std::string advice = "FastResolution";
              if (res.dirTheta < n) advice += " dirTheta >= " + std::to_string(n);
              if (res.dirPhi < n) advice += std::string(res.dirTheta < n ? " and" : "") + " dirPhi >= " + std::to_string(n);
              return advice + " in MultipleScattering.h";
            });
    const Phase& first = settings.firstPhase;
    if (first.kind != PhaseKind::Isotropic) {
      const PhaseResolutionEstimate e = estimatePhaseResolution(first, sunGradedNodes(res.fineTheta));
      if (e.relativeError > tolerance) {
        int n = res.fineTheta;
        while (n < 4096 && estimatePhaseResolution(first, sunGradedNodes(n)).relativeError > tolerance) n = n * 5 / 4 + 1;
        const std::vector<double> nodes = sunGradedNodes(n);
        checks.push_back({"the fast method's " + std::to_string(res.fineTheta) + "-node sun-graded grid", "first", first,
                          sunGradedNodes(res.fineTheta)[1], e, nodes[1],
                          "FastResolution fineTheta >= " + std::to_string(n) + " in MultipleScattering.h"});
      }
    }
  } else {
    const auto& d = settings.dims;
    const double spacing = std::max(kPi / (2.0 * (d[2] - 1)), 2.0 * kPi / (d[1] - 1));
    const auto advise = [&](double needed) {
      const int nV = std::max(d[2], nodesFor(0.5 * kPi, needed));
      const int nP = std::max(d[1], nodesFor(2.0 * kPi, needed));
      return "--res-sc " + std::to_string(d[0]) + "," + std::to_string(nP) + "," + std::to_string(nV) + "," +
             std::to_string(d[3]);
    };
    const std::string grid = "the paper method's " + std::to_string(2 * (d[2] - 1) + 1) + "x" + std::to_string(d[1]) +
                             " direction grid";
    uniform(grid, "later", settings.laterPhase, spacing, advise);
    if (settings.firstPhase != settings.laterPhase)
      uniform(grid, "first", settings.firstPhase, spacing, advise);
  }
  return checks;
}

std::string phaseResolutionWarning(const ScatteringSettings& settings, const std::string& program) {
  constexpr double kTolerance = kPhaseResolutionTolerance, kDeg = 180.0 / kPi;
  const auto checks = checkPhaseResolution(settings, kTolerance);
  if (checks.empty()) return {};
  std::string line = program + ": warning: direction grid too coarse for the phase function:";
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const auto& c = checks[i];
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "%s %s phase %s (g=%.3f; forward peak %.4g sr^-1, half-width %.2f deg) on %s (spacing %.2f deg): "
                  "expected error %.1f%% in 1-g; spacing <= %.2f deg brings it under %.0f%% (%s)",
                  i ? ";" : "", c.which.c_str(), describePhase(c.phase).c_str(), c.estimate.asymmetry,
                  c.estimate.peakValue, c.estimate.peakHalfWidth * kDeg, c.grid.c_str(), c.spacing * kDeg,
                  100.0 * c.estimate.relativeError, c.neededSpacing * kDeg, 100.0 * kTolerance, c.advice.c_str());
    line += buf;
  }
  return line;
}

}  // namespace cloudlut::bake
