// The atmosphere suite of `cloudlut bench` (see BenchSuites.h).
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>

#include "bench/AtmosphereComparison.h"
#include "bench/BenchSuites.h"

namespace cloudlut::bench {
namespace {

std::string sizeOf(const Table4D& t) { return std::to_string(t.dims()[0]) + "x" + std::to_string(t.dims()[1]); }

std::string checkName(const AtmosphereCheck& c) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "sun %+.0f deg, %s", c.sunElevationDeg, c.name.c_str());
  return buf;
}

// A row of the suite; the caller fills the measured fields.
BenchRow row(const std::string& method, const std::string& table, const std::string& variant) {
  BenchRow r;
  r.suite = "atmosphere";
  r.method = method;
  r.table = table;
  r.variant = variant;
  return r;
}

}  // namespace

void benchAtmosphere(BenchReport& report, const BenchOptions& options) {
  const glsl::AtmosphereParameters a = glsl::defaultAtmosphere();
  // bake time on 2 threads (the goal) and on all
  bake::AtmosphereTables tables;
  for (const int threads : {2, options.threads}) {
    if (threads == 0 && options.threads == 0) continue;
    const int n = threads > 0 ? threads : tbb::info::default_concurrency();
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(n));
    const auto t0 = std::chrono::steady_clock::now();
    tables = bake::bakeAtmosphere(a, {}, options.progress);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    BenchRow r = row("bake", "all three", "default Earth");
    r.resolution = sizeOf(tables.transmittance) + "," + sizeOf(tables.multipleScattering) + "," + sizeOf(tables.irradiance);
    r.threads = n;
    r.seconds = seconds;
    r.note = "goal <= 1 s on 2 threads";
    report.add(r);
  }

  const reference::AtmosphereReference ref(a);
  const std::vector<AtmosphereCheck> checks = atmosphereChecks();
  const glm::dvec3 position = checkPosition(a);
  const int steps = options.quick ? 400 : 2000;
  const int paths = options.quick ? 4000 : 40000;
  std::vector<glm::dvec3> single(checks.size()), transmittance(checks.size());
  std::vector<reference::AtmosphereRadiance> all(checks.size());
  tbb::parallel_for(std::size_t{0}, checks.size(), [&](std::size_t i) {
    const AtmosphereCheck& c = checks[i];
    single[i] = ref.singleScattering(position, c.view, c.sun, steps);
    all[i] = ref.allOrders(position, c.view, c.sun, paths, 1000 + i);
    transmittance[i] = ref.transmittanceToTop(position.y, c.view.y);
  });

  const glsl::AtmosphereTexture tt = bake::atmosphereTexture(tables.transmittance);
  double worstT = 0.0, worstS = 0.0, worstA = 0.0;
  for (std::size_t i = 0; i < checks.size(); ++i) {
    const AtmosphereCheck& c = checks[i];
    const std::string name = checkName(c);
    if (c.sunElevationDeg == 90.0) {  // the view's transmittance does not depend on the sun
      const glm::dvec3 T(glsl::transmittanceToTop(a, tt, float(position.y), float(c.view.y)));
      const double e = relativeError(T, transmittance[i]);
      worstT = std::max(worstT, e);
      BenchRow r = row("table", "transmittance", c.name);
      r.resolution = sizeOf(tables.transmittance);
      r.errorMean = r.errorMax = e;
      r.note = "goal 0.5%";
      report.add(r);
    }
    const double eS = relativeError(tableSkyRadiance(tables, a, c, 1), single[i]);
    worstS = std::max(worstS, eS);
    BenchRow rs = row("sky", "single", name);
    rs.steps = glsl::CLOUDLUT_SKY_STEPS;
    rs.errorMean = rs.errorMax = eS;
    rs.note = "goal 2%";
    report.add(rs);
    const double eA = relativeError(tableSkyRadiance(tables, a, c, 0), all[i].value);
    const double noise = relativeError(all[i].value + all[i].standardError, all[i].value);
    worstA = std::max(worstA, eA);
    char note[96];
    std::snprintf(note, sizeof note, "goal 5%%; reference standard error %.2f%%", 100.0 * noise);
    BenchRow ra = row("sky", "all orders", name);
    ra.steps = glsl::CLOUDLUT_SKY_STEPS;
    ra.errorMean = ra.errorMax = eA;
    ra.note = note;
    report.add(ra);
  }
  {
    BenchRow r = row("worst", "transmittance", "");
    r.errorMax = worstT;
    report.add(r);
  }
  {
    BenchRow r = row("worst", "single", "");
    r.errorMax = worstS;
    report.add(r);
  }
  {
    BenchRow r = row("worst", "all orders", "");
    r.errorMax = worstA;
    report.add(r);
  }
}

}  // namespace cloudlut::bench
