#include "bake/LutSetBake.h"

#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <utility>

#include "bake/AngularClosureBaker.h"
#include "core/Defaults.h"
#include "core/ReferenceParticle.h"
#include "io/BackgroundTableWrites.h"
#include "io/LutSetTransaction.h"
#include "scene/AtmosphereJson.h"

namespace cloudlut::bake {

namespace {

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void done(const std::function<void()>& stageDone) {
  if (stageDone) stageDone();
}

// printf into a string.
#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
void appendf(std::string& out, const char* format, ...) {
  char buf[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  out += buf;
}

}  // namespace

nlohmann::json bakeLutSet(LutSetPlan& plan, const ProgressFn& progress, const std::function<void()>& stageDone) {
  // Everything is written into a staging directory and swapped in at the end (io/LutSetTransaction.h).
  io::LutSetTransaction transaction(plan.out);
  const std::filesystem::path& dir = transaction.stagingDir();
  // Each table's files are written in the background while the next table is baked (declared
  // after the transaction: every write ends before an unwinding transaction removes its files).
  io::BackgroundTableWrites writes;
  nlohmann::json timings = nlohmann::json::object();
  nlohmann::json forScene = nlohmann::json::object();
  // the optical-depth table the multiple table's angular closure is computed against
  std::optional<Table4D> closureDepth;
  if (plan.opticalDepth) {
    const auto t0 = std::chrono::steady_clock::now();
    const ReferenceParticle particle(plan.model, plan.seed);
    if (plan.forScene) {
      reportProgress(progress, "choosing the resolution", 0.0);
      const int steps = plan.od.steps > 0 ? plan.od.steps : defaultSteps(plan.model);
      const OpticalDepthChoice choice = chooseOpticalDepthResolution(particle, *plan.forScene, plan.tolerance,
                                                                     plan.od.extinction * plan.od.radius, steps);
      plan.od.dims = choice.dims;
      forScene["optical_depth_dims"] = choice.dims;
      forScene["optical_depth_opacity_error_p95"] = choice.errorP95;
    }
    const auto tBake = std::chrono::steady_clock::now();
    Table4D table = bakeOpticalDepth(particle, plan.od, progress);
    forScene["optical_depth_bake_s"] = secondsSince(tBake);
    timings["optical_depth_s"] = secondsSince(t0);
    done(stageDone);
    if (plan.sc.multiple && plan.angularClosure) closureDepth = table;
    writes.write(std::move(table), plan.precision, dir, plan.formats);
  }
  nlohmann::json scatteringReport;
  if (plan.scattering() && plan.forScene) {
    reportProgress(progress, "choosing the scattering resolution", 0.0);
    const ScatteringChoice choice = chooseScatteringResolution(plan.sc, plan.tolerance);
    plan.sc.dims = choice.dims;
    forScene["scattering_dims"] = plan.sc.dims;
    forScene["scattering_slices_per_octave"] = choice.slicesPerOctave;
    forScene["single_scattering_error_p95_at_slices"] = choice.angularErrorP95;
    forScene["single_scattering_error_p95"] = choice.errorP95;
  }
  if (plan.scattering()) {
    const auto t0 = std::chrono::steady_clock::now();
    ScatteringResult result = bakeScattering(plan.sc, progress);
    timings["scattering_s"] = secondsSince(t0);
    done(stageDone);
    if (result.multiple && closureDepth) {
      const auto tClosure = std::chrono::steady_clock::now();
      attachAngularClosure(*result.multiple, *closureDepth, ReferenceParticle(plan.model, plan.seed),
                           plan.sc.firstPhase, plan.sc.laterPhase, plan.closure, progress);
      timings["angular_closure_s"] = secondsSince(tClosure);
      done(stageDone);
    }
    // Radiance is not confined to [0, 1]: 8-bit storage is for the optical-depth table only.
    const io::SampleType type = plan.precision == io::SampleType::U8 ? io::SampleType::Half : plan.precision;
    for (std::optional<Table4D>* t : {&result.single, &result.multiple})
      if (*t) writes.write(std::move(**t), type, dir, plan.formats);
    scatteringReport = result.report;
  }

  if (plan.atmosphere) {
    const auto t0 = std::chrono::steady_clock::now();
    AtmosphereTables atmosphere = bakeAtmosphere(plan.atmosphereParameters, {}, progress);
    timings["atmosphere_s"] = secondsSince(t0);
    done(stageDone);
    // radiance and irradiance are not confined to [0, 1]: no 8-bit storage
    const io::SampleType type = plan.precision == io::SampleType::U8 ? io::SampleType::Half : plan.precision;
    for (Table4D* t :
         {&atmosphere.transmittance, &atmosphere.multipleScattering, &atmosphere.irradiance})
      writes.write(std::move(*t), type, dir, plan.formats);
  }

  nlohmann::json manifest = io::makeManifest(plan.generator, writes.finish());
  manifest["parameters"] = {{"extinction_per_m", plan.od.extinction}, {"radius_m", plan.od.radius},
                            {"density_model", toString(plan.model)}, {"seed", plan.seed}};
  if (plan.scattering()) {
    manifest["parameters"]["orders"] = plan.sc.orders > 0 ? nlohmann::json(plan.sc.orders) : nlohmann::json("converged");
    manifest["parameters"]["method"] = toString(plan.sc.method);
    manifest["scattering_report"] = scatteringReport;
  }
  if (plan.atmosphere) manifest["atmosphere"] = scene::atmosphereToJson(plan.atmosphereParameters);
  manifest["bake_seconds"] = timings;
  if (plan.forScene) {
    forScene["scene"] = plan.forScene->source;
    forScene["kind"] = plan.forScene->kind;
    forScene["density_range"] = {plan.forScene->rhoMin, plan.forScene->rhoMax};
    forScene["tolerance"] = plan.tolerance;
    manifest["for_scene"] = forScene;
  }
  io::writeManifest(dir, manifest);
  for (const std::string& warning : transaction.commit())
    std::fprintf(stderr, "cloudlut bake: warning: %s\n", warning.c_str());
  return manifest;
}

std::string forSceneSummary(const LutSetPlan& plan, const nlohmann::json& manifest) {
  if (!plan.forScene) return {};
  const SceneNeeds& needs = *plan.forScene;
  const nlohmann::json forScene = manifest.value("for_scene", nlohmann::json::object());
  const nlohmann::json timings = manifest.value("bake_seconds", nlohmann::json::object());
  std::string out;
  appendf(out, "for scene %s (%s", needs.source.c_str(), needs.kind.c_str());
  if (needs.particles) appendf(out, ", %zu particles", needs.particles);
  appendf(out, "): density scales %.4g to %.4g\n", static_cast<double>(needs.rhoMin), static_cast<double>(needs.rhoMax));
  double bytes = 0, defaultBytes = 0, seconds = 0, defaultSeconds = 0;
  const double sampleBytes = plan.precision == io::SampleType::Float ? 4 : 2;
  if (plan.opticalDepth) {
    const auto& d = plan.od.dims;
    const auto& dd = defaults::kOpticalDepthDims;
    const double nodes = double(d[0]) * d[1] * d[2] * d[3], defaultNodes = double(dd[0]) * dd[1] * dd[2] * dd[3];
    const double odBytes = plan.precision == io::SampleType::U8 ? 1 : sampleBytes;
    bytes += 2 * odBytes * nodes;
    defaultBytes += 2 * odBytes * defaultNodes;
    const double t = forScene.value("optical_depth_bake_s", 0.0);
    seconds += t;
    defaultSeconds += t * defaultNodes / nodes;  // the bake's time is proportional to its chords
    const double err = forScene.value("optical_depth_opacity_error_p95", 0.0), tol = forScene.value("tolerance", 0.0);
    appendf(out, "  optical depth: %dx%dx%dx%d (95th-percentile opacity error %.4f, tolerance %.4f%s)\n", d[0], d[1],
            d[2], d[3], err, tol, err > tol ? "; NOT met: the largest table a GL 3D texture holds" : "");
  }
  if (plan.scattering()) {
    const auto& d = plan.sc.dims;
    const int tables = int(plan.sc.single) + int(plan.sc.multiple);
    bytes += tables * sampleBytes * double(d[0]) * d[1] * d[2] * d[3];
    const auto& dd = defaults::kScatteringDims;
    defaultBytes += tables * sampleBytes * double(dd[0]) * dd[1] * dd[2] * dd[3];
    const double t = timings.value("scattering_s", 0.0);
    seconds += t;
    defaultSeconds += t * dd[3] / d[3];  // each density slice costs about the same (the volume solve dominates)
    appendf(out, "  scattering: density slices log2 rho = %g..%g, %d per octave (the default: %d..%d, 1 per octave)\n",
            plan.sc.sMin, plan.sc.sMax, forScene.value("scattering_slices_per_octave", 1), defaults::kDensitySlopeMin,
            defaults::kDensitySlopeMax);
    if (forScene.contains("single_scattering_error_p95")) {
      const double err = forScene.value("single_scattering_error_p95", 0.0), tol = forScene.value("tolerance", 0.0);
      appendf(out,
              "  scattering: %dx%dx%dx%d (95th-percentile single-scattering error %.4f at the slices, %.4f between "
              "them; tolerance %.4f%s)\n",
              d[0], d[1], d[2], d[3], forScene.value("single_scattering_error_p95_at_slices", 0.0), err, tol,
              err > tol ? "; NOT met by the largest candidate" : "");
    }
  }
  appendf(out, "  saved: %.1f of %.1f MB per format (%.0f%%), about %.1f of %.1f s (estimated from this bake's rates)\n",
          (defaultBytes - bytes) / 1e6, defaultBytes / 1e6, 100.0 * (defaultBytes - bytes) / defaultBytes,
          defaultSeconds - seconds, defaultSeconds);
  return out;
}

}  // namespace cloudlut::bake
