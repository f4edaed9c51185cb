// The "tables" suite of `cloudlut bench`: the scattering tables' layout chosen by measurement
// (issue 15): bytes of one table in half precision against the single-scattering error at
// random geometry, on the density slices and between them, for φv over [0, 2π] or folded onto
// [0, π], 1, 2 or 4 density slices per octave, and interpolation between the slices linear in
// log2 ρ or in ρ (densityAxisLinearInRho, cloudlut_geometry.glsl).
//
// Reference: the Monte Carlo estimator of the homogeneous sphere (reference/SphereMonteCarlo.h,
// order 1 only), independent of the baker. Queries: rays as a distant camera sees them, at
// every integer log2 ρ from −4 to 3 ("on slices": a node of every layout) and at densities
// log-uniform over [2^−4, 2^3] ("between": wherever they fall). error_p95 is the 95th
// percentile of |table·P1 − MC| / MC over the between rows (rows carrying ≥ 1% of the mean);
// the note holds the on-slice p95 and the bytes. Single scattering is the sharpest of the
// two tables (the terminator); the multiple table's rows are in the scattering suite.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "bake/ScatteringBaker.h"
#include "bench/BenchSuites.h"
#include "core/Defaults.h"
#include "core/Glsl.h"
#include "core/TableLookup.h"
#include "core/SphereRays.h"
#include "reference/SphereMonteCarlo.h"

namespace cloudlut::bench {
namespace {

struct Ray {
  glm::dvec3 S, v, l;
  double rho;
  bool between;
};

// Rays as a distant camera sees them: S uniform, v cosine-weighted about the inward normal.
std::vector<Ray> makeRays(int perGroup) {
  std::mt19937_64 rng(1515);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const auto unit = [&] {
    const double z = 2.0 * u(rng) - 1.0, p = 6.283185307179586 * u(rng), r = std::sqrt(1.0 - z * z);
    return glm::dvec3(r * std::cos(p), r * std::sin(p), z);
  };
  std::vector<Ray> rays;
  const int octaves = defaults::kDensitySlopeMax - defaults::kDensitySlopeMin;
  for (int g = 0; g < 2 * (octaves + 1); ++g)
    for (int i = 0; i < perGroup; ++i) {
      Ray r;
      r.S = unit();
      r.l = unit();
      const double u1 = u(rng), u2 = u(rng);
      r.v = cosineWeightedInward(r.S, u1, u2);
      r.between = g > octaves;
      r.rho = std::exp2(r.between ? defaults::kDensitySlopeMin + octaves * u(rng) : defaults::kDensitySlopeMin + g);
      rays.push_back(r);
    }
  return rays;
}

struct Layout {
  bool fold;
  int perOctave;
  bool linearInRho;
};

}  // namespace

void benchTableLayout(BenchReport& report, const BenchOptions& options) {
  const int cores = options.threads > 0 ? options.threads : 2;
  const std::vector<Ray> rays = makeRays(options.quick ? 20 : 80);
  std::vector<reference::SphereMcQuery> q;
  for (const Ray& r : rays) q.push_back({r.S, r.v, r.l, defaults::kUnitOpticalRadius * r.rho});
  reference::SphereMcSettings ms;
  ms.paths = options.quick ? 4000 : 40000;
  ms.seed = 1515;
  ms.maxOrder = 1;
  reportProgress(options.progress, "bench: tables reference", 0.0);
  const auto mc = reference::estimateSphereRadiance(q, ms, options.progress);
  double mean[2] = {0.0, 0.0};
  std::size_t count[2] = {0, 0};
  for (std::size_t i = 0; i < rays.size(); ++i) {
    mean[rays[i].between] += mc[i].single;
    ++count[rays[i].between];
  }
  for (int g = 0; g < 2; ++g) mean[g] /= static_cast<double>(std::max<std::size_t>(1, count[g]));

  const std::vector<Layout> layouts = options.quick
      ? std::vector<Layout>{{false, 1, false}, {true, 2, true}}
      : std::vector<Layout>{{false, 1, false}, {true, 1, false}, {true, 1, true}, {true, 2, false},
                            {true, 2, true},   {false, 2, true}, {true, 4, false}, {true, 4, true}};
  const int octaves = defaults::kDensitySlopeMax - defaults::kDensitySlopeMin;
  for (std::size_t k = 0; k < layouts.size(); ++k) {
    const Layout& lay = layouts[k];
    reportProgress(options.progress, "bench: tables", static_cast<double>(k) / static_cast<double>(layouts.size()));
    bake::ScatteringSettings s;
    s.dims = {32, lay.fold ? 33 : 64, 16, octaves * lay.perOctave + 1};
    s.foldPhiV = lay.fold;
    s.densityLinearInRho = lay.linearInRho;
    s.multiple = false;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(cores));
    const auto t0 = std::chrono::steady_clock::now();
    const bake::ScatteringResult r = bake::bakeScattering(s);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::vector<double> e[2];
    for (std::size_t i = 0; i < rays.size(); ++i) {
      const Ray& ray = rays[i];
      const double ref = mc[i].single;
      if (!(ref >= 0.01 * mean[ray.between])) continue;
      const double p1 = phaseValue(defaults::kFirstPhase, static_cast<float>(glm::dot(ray.v, ray.l)));
      const double table = p1 * lookupScattering(*r.single, glm::vec3(ray.S), glm::vec3(ray.v), glm::vec3(ray.l),
                                                 static_cast<float>(ray.rho));
      e[ray.between].push_back(std::abs(table - ref) / ref);
    }
    const ErrorStats on = summarizeErrors(e[0]), between = summarizeErrors(e[1]);
    const long long bytes = 2LL * s.dims[0] * s.dims[1] * s.dims[2] * s.dims[3];
    const std::string resolution = std::to_string(s.dims[0]) + "x" + std::to_string(s.dims[1]) + "x" +
                                   std::to_string(s.dims[2]) + "x" + std::to_string(s.dims[3]);
    char note[256];
    std::snprintf(note, sizeof note, "bytes %lld (half); on-slice p95 %.4f; between p95 %.4f; phi_v %s; %d per octave; %s",
                  bytes, on.p95, between.p95, lay.fold ? "folded" : "full", lay.perOctave,
                  lay.linearInRho ? "linear in rho" : "linear in log2 rho");
    report.add({"tables", lay.fold ? "folded" : "full", "single_scattering", lay.linearInRho ? "linear-rho" : "linear-log-rho",
                resolution, "1", static_cast<int>(bytes), cores, seconds, between.mean, between.p95, between.max, -1, note});
  }
  reportProgress(options.progress, "bench: tables", 1.0);
}

}  // namespace cloudlut::bench
