// The Monte Carlo reference for the homogeneous sphere against closed forms and itself:
// axis chords with closed-form single scattering, the thin-medium limit, energy conservation
// of the photon tracer, the backward estimator's normalisation against forward photon
// tracing, the photon-tracing table of docs/MEASURED.md, thread-count determinism and the CLI verb.
#include <catch2/catch.hpp>

#include <tbb/global_control.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "support/CliRunner.h"
#include "core/Glsl.h"
#include "core/PhaseSampling.h"
#include "reference/SphereMonteCarlo.h"

using namespace cloudlut;
using namespace cloudlut::reference;

namespace {

double phase(const Phase& p, double mu) {
  return static_cast<double>(phaseValue(p, static_cast<float>(mu)));
}

SphereMcEstimate estimateOne(const SphereMcQuery& q, const SphereMcSettings& s) {
  return estimateSphereRadiance({q}, s).front();
}

}  // namespace

TEST_CASE("MC single scattering matches closed forms on the axis", "[reference]") {
  SphereMcSettings s;
  s.paths = 40000;
  const glm::dvec3 l(0, 0, 1);
  for (double sigma : {0.5, 2.0, 12.0}) {
    // Entering at the sun-facing pole, looking straight down: d_sun = t, so
    // L1 = ∫_0^2 σ e^{-2σt} dt = (1 - e^{-4σ}) / 2, scattering angle cos = v·l = -1.
    const auto lit = estimateOne({l, -l, l, sigma}, s);
    const double litExact = phase(s.first, -1.0) * 0.5 * (1.0 - std::exp(-4.0 * sigma));
    CHECK(std::abs(lit.single - litExact) < 4.0 * lit.singleSe + 1e-12);
    // Entering at the dark pole looking at the sun: d_sun = 2 - t, so every point of the chord
    // contributes σ e^{-2σ}: L1 = 2σ e^{-2σ}.
    const auto dark = estimateOne({-l, l, l, sigma}, s);
    const double darkExact = phase(s.first, 1.0) * 2.0 * sigma * std::exp(-2.0 * sigma);
    CHECK(std::abs(dark.single - darkExact) <= 4.0 * dark.singleSe);
  }
}

TEST_CASE("MC thin-medium limit: single = P1 · σ · chord", "[reference]") {
  SphereMcSettings s;
  s.paths = 4096;
  const double sigma = 1e-4;
  const glm::dvec3 S = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  const glm::dvec3 v = glm::normalize(glm::dvec3(-0.2, 0.6, -0.9));
  const glm::dvec3 l = glm::normalize(glm::dvec3(0.4, 0.1, 0.5));
  const auto e = estimateOne({S, v, l, sigma}, s);
  const double chord = -2.0 * glm::dot(S, v);
  const double expected = phase(s.first, glm::dot(v, l)) * sigma * chord;
  CHECK(e.single == Approx(expected).epsilon(2e-3));
  // Multiple scattering is of order σ²: negligible.
  CHECK(e.multipleAll < 1e-3 * e.single);
}

TEST_CASE("Photon tracing conserves energy and matches the unscattered closed form", "[reference]") {
  for (double sigma : {0.8, 6.4}) {
    const auto p = photonTraceSphere(sigma, defaults::kFirstPhase, defaults::kLaterPhase, 20000, 3, 18);
    CHECK(p.total == Approx(1.0).margin(1e-9));  // a non-absorbing sphere returns everything
    CHECK(p.unscattered == Approx(unscatteredShare(sigma)).margin(0.004));
  }
  // Closed form against a direct integration of e^{-σ·chord} over the disk.
  const double sigma = 1.7;
  double sum = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double b = (i + 0.5) / n;
    sum += 2.0 * b * std::exp(-2.0 * sigma * std::sqrt(1.0 - b * b)) / n;
  }
  CHECK(unscatteredShare(sigma) == Approx(sum).epsilon(1e-6));
}

TEST_CASE("Backward estimator integrated over the sphere agrees with forward photon tracing", "[reference]") {
  SphereMcSettings s;
  const double sigma = 3.2;
  const auto fwd = photonTraceSphere(sigma, s.first, s.later, 200000, 9, 18);
  const auto bwd = integrateBackwardShares(sigma, s, 200000);
  double m18 = 0.0;
  for (int k = 2; k <= 18; ++k) m18 += fwd.byOrder[k];
  const double mAll = m18 + fwd.beyond;
  const double tol = 4.0 * fwd.standardError;
  CHECK(bwd.single == Approx(fwd.byOrder[1]).margin(4.0 * bwd.singleSe + tol));
  CHECK(bwd.multipleN == Approx(m18).margin(4.0 * bwd.multipleNSe + tol));
  CHECK(bwd.multipleAll == Approx(mAll).margin(4.0 * bwd.multipleAllSe + tol));
  // Everything that does not cross unscattered leaves scattered.
  CHECK(bwd.single + bwd.multipleAll == Approx(1.0 - unscatteredShare(sigma)).margin(0.02));
}

TEST_CASE("Photon tracing reproduces the measured table of docs/MEASURED.md (HG 0.9 then 0.7)", "[reference]") {
  struct Row { double rho, unscattered, single, m18, beyond; };
  const Row rows[] = {{1.0 / 16, 0.369, 0.345, 0.286, 0.000}, {0.25, 0.048, 0.111, 0.837, 0.004},
                      {0.5, 0.012, 0.048, 0.827, 0.112},      {1.0, 0.003, 0.029, 0.620, 0.348}};
  for (const Row& r : rows) {
    const auto p = photonTraceSphere(defaults::kUnitOpticalRadius * r.rho, {PhaseKind::HenyeyGreenstein, 0.9f},
                                     {PhaseKind::HenyeyGreenstein, 0.7f}, 40000, 17, 18);
    double m18 = 0.0;
    for (int k = 2; k <= 18; ++k) m18 += p.byOrder[k];
    CHECK(p.unscattered == Approx(r.unscattered).margin(0.01));
    CHECK(p.byOrder[1] == Approx(r.single).margin(0.01));
    CHECK(m18 == Approx(r.m18).margin(0.01));
    CHECK(p.beyond == Approx(r.beyond).margin(0.01));
  }
}

TEST_CASE("MC phase sampling reproduces the phase functions' mean cosine", "[reference]") {
  // <mu> of HG is g; of Cornette–Shanks 3g(g² + 4) / (5(2 + g²)).
  McRng rng(1, 2, 3);
  const int n = 400000;
  for (const Phase& p : {Phase{PhaseKind::HenyeyGreenstein, 0.7f}, Phase{PhaseKind::CornetteShanks, 0.9f},
                        Phase{PhaseKind::Isotropic, 0.0f}}) {
    double m = 0.0;
    for (int i = 0; i < n; ++i) m += samplePhaseCosine(p, rng);
    m /= n;
    const double g = p.param;
    const double expected = p.kind == PhaseKind::HenyeyGreenstein ? g
                           : p.kind == PhaseKind::CornetteShanks ? 3.0 * g * (g * g + 4.0) / (5.0 * (2.0 + g * g))
                                                                 : 0.0;
    CHECK(m == Approx(expected).margin(0.005));
  }
  // Jendersie–d'Eon at 10 µm: the mean cosine by quadrature of the phase function itself.
  const Phase jd{PhaseKind::JendersieDeon, 10.0f};
  double m = 0.0, q = 0.0;
  const int steps = 2000000;
  for (int i = 0; i < steps; ++i) {
    const double mu = -1.0 + 2.0 * (i + 0.5) / steps;
    const double f = phase(jd, mu) * 2.0 * 3.14159265358979 * 2.0 / steps;
    q += f;
    m += mu * f;
  }
  CHECK(q == Approx(1.0).margin(0.01));
  double ms = 0.0;
  for (int i = 0; i < n; ++i) ms += samplePhaseCosine(jd, rng);
  CHECK(ms / n == Approx(m / q).margin(0.005));
}

TEST_CASE("MC scattered directions: the azimuth is drawn before the cosine, on every compiler", "[reference]") {
  // sampleScatteredDirection draws the azimuth's uniform number, then the cosine; the same draws
  // written out by hand must give the same direction bit for bit (as one call with both draws
  // as arguments, the order was the compiler's). And the sampled cosine against d must be the
  // phase function's: its mean for Henyey–Greenstein is g.
  const Phase hg{PhaseKind::HenyeyGreenstein, 0.7f};
  McRng a(4, 5, 6), b(4, 5, 6);
  glm::dvec3 d = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  double meanCosine = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 next = sampleScatteredDirection(d, hg, a);
    const double azimuth = b.next();
    const double mu = samplePhaseCosine(hg, b);
    const glm::dvec3 byHand = rotateAbout(d, mu, azimuth);
    if (i < 1000) REQUIRE((next.x == byHand.x && next.y == byHand.y && next.z == byHand.z));
    meanCosine += glm::dot(next, d);
    d = next;
  }
  CHECK(meanCosine / n == Approx(0.7).margin(0.005));
}

TEST_CASE("MC estimates do not depend on the number of threads", "[reference]") {
  SphereMcSettings s;
  s.paths = 5000;
  std::vector<SphereMcQuery> q;
  for (int i = 0; i < 5; ++i) {
    const double a = 0.7 * i;
    const glm::dvec3 S(std::cos(a), std::sin(a), 0.0);
    q.push_back({S, glm::normalize(-S + glm::dvec3(0.1, 0.2, 0.3)), glm::dvec3(0, 0, 1), 0.5 + i * 3.0});
  }
  std::vector<SphereMcEstimate> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = estimateSphereRadiance(q, s);
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = estimateSphereRadiance(q, s);
  }
  for (std::size_t i = 0; i < q.size(); ++i) {
    CHECK(one[i].single == two[i].single);
    CHECK(one[i].multipleN == two[i].multipleN);
    CHECK(one[i].multipleAll == two[i].multipleAll);
    CHECK(one[i].multipleAllSe == two[i].multipleAllSe);
  }
}

TEST_CASE("cloudlut reference sphere writes estimates with standard errors", "[reference][cli]") {
  test::TempDir dir;
  {
    std::ofstream f(dir / "in.csv");
    f << "sx,sy,sz,vx,vy,vz,lx,ly,lz,density\n";
    f << "0,0,1,0,0,-1,0,0,1,1\n";
    f << "1,0,0,-0.8,0.6,0,0,0,1,0.25\n";
  }
  const std::string csv = "'" + (dir / "in.csv").string() + "'";
  const auto r = test::runCli("reference sphere --csv " + csv + " --paths 3000 --threads 2 --quiet");
  REQUIRE(r.exitCode == 0);
  std::istringstream in(r.out);
  std::string line;
  std::getline(in, line);
  CHECK(line == "sx,sy,sz,vx,vy,vz,lx,ly,lz,density,single,single_se,multiple18,multiple18_se,multiple_all,multiple_all_se");
  int rows = 0;
  while (std::getline(in, line)) {
    ++rows;
    int commas = 0;
    for (char c : line) commas += c == ',';
    CHECK(commas == 15);
  }
  CHECK(rows == 2);
  const auto bad = test::runCli("reference sphere --csv " + csv + " --phase xx");
  CHECK(bad.exitCode == 2);
  const auto noTarget = test::runCli("reference --csv " + csv);
  CHECK(noTarget.exitCode == 2);
  const auto missing = test::runCli("reference sphere --csv '" + (dir / "nope.csv").string() + "'");
  CHECK(missing.exitCode == 1);
}
