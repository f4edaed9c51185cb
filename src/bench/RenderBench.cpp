// The render suite of `cloudlut bench` (see BenchSuites.h): Renderer II cloudscapes per quality
// preset (seed Table 1) and blend mode, milliseconds per stage, and temporal stability over a
// slow camera move. llvmpipe (OSMesa) on the CPU: absolute times are those of a software GPU;
// ratios between rows are the figures to read.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "bake/OpticalDepthBaker.h"
#include "bake/ScatteringBaker.h"
#include "bench/BenchSuites.h"
#include "core/Defaults.h"
#include "core/Glsl.h"
#include "core/ReferenceParticle.h"
#include "core/TableLookup.h"
#include "scene/Cloudscape.h"
#include "render/GlContext.h"
#include "render/Renderer.h"

namespace cloudlut::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Synthetic scattering table on the documented axes (the timing does not depend on the values;
// the baked scattering tables may not exist yet when the suite runs).
Table4D syntheticScattering(const std::string& name, bool single) {
  const std::array<int, 4> dims = {16, 24, 8, 8};
  std::array<Axis, 4> axes = {Axis{"theta_s", "rad", 0.0, kPi, dims[0], false, bake::sunZenithWarp(dims[0])},
                              Axis{"phi_v", "rad", 0.0, 2.0 * kPi, dims[1], true},
                              Axis{"theta_v", "rad", 0.0, 0.5 * kPi, dims[2], false},
                              Axis{"log2_density", "log2", -4.0, 3.0, dims[3], false}};
  Table4D t(name, axes, {Channel{single ? kSingleScatteringChannel : kMultipleScatteringChannel, "synthetic"}});
  for (int i3 = 0; i3 < dims[3]; ++i3)
    for (int i2 = 0; i2 < dims[2]; ++i2)
      for (int i1 = 0; i1 < dims[1]; ++i1)
        for (int i0 = 0; i0 < dims[0]; ++i0) {
          const double ts = axes[0].value(i0), tv = axes[2].value(i2), s = axes[3].value(i3);
          const double v = single ? 0.05 * std::exp2(0.25 * s) * (1.0 + 0.4 * std::cos(ts)) * (0.6 + 0.4 * std::cos(tv))
                                  : 0.08 * (1.0 + 0.5 * std::tanh(0.5 * s)) * (1.0 + 0.5 * std::cos(ts));
          t.at(t.index(i0, i1, i2, i3), 0) = single ? glsl::singleScatteringToTable(static_cast<float>(v)) : static_cast<float>(v);
        }
  // built first, then moved in: clang 14 leaks the old value of `json& = {init-list}`
  nlohmann::json parameters = {{"extinction_per_m", defaults::kExtinctionPerMetre},
                               {"radius_m", defaults::kParticleRadiusMetres},
                               {"synthetic", true}};
  t.parameters() = std::move(parameters);
  if (single) t.parameters()["first_phase"] = phaseToJson(defaults::kFirstPhase);
  return t;
}

}  // namespace

io::LutSet renderBenchLuts() {
  io::LutSet set;
  set.dir = "(bench: baked 32x16x32x16 noise optical depth, synthetic scattering)";
  bake::OpticalDepthSettings s;
  s.dims = {32, 16, 32, 16};
  set.tables["optical_depth"] = io::LoadedTable{bake::bakeOpticalDepth(ReferenceParticle(DensityModel::Noise, 1), s),
                                                io::SampleType::Float, true, {}};
  set.tables["single_scattering"] = io::LoadedTable{syntheticScattering("single_scattering", true), io::SampleType::Float, true, {}};
  set.tables["multiple_scattering"] = io::LoadedTable{syntheticScattering("multiple_scattering", false), io::SampleType::Float, true, {}};
  return set;
}

namespace {

// Mean, 95th percentile and max of the per-pixel |change| of the composited radiance
// (radiance + T · sky, averaged over R, G, B) between two frames.
ErrorStats frameChange(const render::Image& a, const render::Image& b, const glm::vec3& sky) {
  std::vector<double> d(static_cast<std::size_t>(a.width) * a.height);
  for (std::size_t i = 0; i < d.size(); ++i) {
    double sum = 0;
    for (int c = 0; c < 3; ++c) {
      const double ca = a.rgba[4 * i + c] + (1.0 - a.rgba[4 * i + 3]) * sky[c];
      const double cb = b.rgba[4 * i + c] + (1.0 - b.rgba[4 * i + 3]) * sky[c];
      sum += std::abs(ca - cb);
    }
    d[i] = sum / 3.0;
  }
  return summarizeErrors(std::move(d));
}

// N unit spheres (ρ = 1) at uniform random points of a slab 8 units thick whose area grows with N
// (1.5² units² per particle: a cloud layer that widens, not one that packs tighter), fixed seed.
std::vector<scene::Particle> slabParticles(std::size_t n) {
  std::mt19937 rng(12345u);
  const float side = 1.5f * std::sqrt(static_cast<float>(n));
  std::uniform_real_distribution<float> across(-0.5f * side, 0.5f * side), up(0.0f, 8.0f);
  std::vector<scene::Particle> out(n);
  for (scene::Particle& p : out) {
    const float x = across(rng), z = across(rng), y = up(rng);
    p.center = {x, y, z};
  }
  return out;
}

// Time against particle count (1e4, 1e5, 1e6 explicit particles, 640×360, alpha blending): the
// seed's per-particle occlusion (LightOcclusion) and the cloud lighting's sun volume, each time
// as a ratio against the 1e5 case of the same run.
void benchParticleCount(BenchReport& report, const BenchOptions& options, render::Renderer& renderer) {
  const int width = 640, height = 360;
  const std::string res = std::to_string(width) + "x" + std::to_string(height);
  const std::vector<std::size_t> counts =
      options.quick ? std::vector<std::size_t>{10000, 100000} : std::vector<std::size_t>{10000, 100000, 1000000};
  for (const render::LightingModel lighting : {render::LightingModel::Seed, render::LightingModel::Cloud}) {
    double at1e5 = 0;
    std::vector<std::pair<std::size_t, render::RenderStats>> measured;
    for (const std::size_t n : counts) {
      const std::vector<scene::Particle> particles = slabParticles(n);
      const float side = 1.5f * std::sqrt(static_cast<float>(n));
      render::RenderSettings s;
      s.width = width;
      s.height = height;
      s.lighting = lighting;
      s.sunlight = render::defaultSunlight(lighting);
      s.view.camera.target = {0.0f, 4.0f, 0.0f};
      s.view.camera.eye = {0.0f, 0.45f * side + 10.0f, 0.75f * side + 10.0f};
      s.view.camera.fovDeg = 60.0f;
      s.view.lighting.sunDirection = glm::normalize(glm::vec3(0.5f, 0.8f, 0.3f));
      render::RenderStats st;
      renderer.render(particles, s, &st);
      if (n == 100000) at1e5 = st.occlusionSeconds;
      measured.emplace_back(n, st);
    }
    for (const auto& [n, st] : measured) {
      char note[200];
      std::snprintf(note, sizeof note, "%s; time / time at 1e5 %.2f; upload %.0f ms, shading %.0f ms, %zu cover entries dropped",
                    lighting == render::LightingModel::Seed ? "seed: per-particle occlusion (light-space tiles)"
                                                            : "cloud: sun optical-depth volume",
                    at1e5 > 0 ? st.occlusionSeconds / at1e5 : 0.0, 1e3 * st.uploadSeconds, 1e3 * st.renderSeconds,
                    st.tileOverflow);
      report.add(BenchRow{"render", "particle-count", "sunlight", render::toString(lighting), res, "",
                          static_cast<int>(n), 0, st.occlusionSeconds, -1, -1, -1, -1, note});
    }
  }
}

}  // namespace

void benchRender(BenchReport& report, const BenchOptions& options) {
  const int width = options.quick ? 320 : 640, height = options.quick ? 180 : 360;
  const int frames = options.quick ? 4 : 8;
  const std::string res = std::to_string(width) + "x" + std::to_string(height);
  const io::LutSet luts = renderBenchLuts();
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  render::Renderer renderer(*context, luts);
  const scene::CloudscapeScene scene = scene::loadCloudscape(scene::kDefaultCloudscape);
  scene::Scene empty;
  empty.view = scene.view;
  const scene::View view = scene::resolveView(empty, {});
  const auto& qualities = scene::qualityPresetNames();
  int step = 0;
  const int steps = static_cast<int>(qualities.size()) * 2;
  for (const std::string& qname : qualities) {
    const scene::QualityPreset q = scene::qualityPreset(qname);
    for (render::BlendMode blend : {render::BlendMode::Alpha, render::BlendMode::Volume}) {
      reportProgress(options.progress, "bench: render", static_cast<double>(step++) / steps);
      render::RenderSettings s;
      s.width = width;
      s.height = height;
      s.view = view;
      s.blend = blend;
      const std::string method = render::toString(blend);
      const std::string variant = qname + " " + std::to_string(q.ringDim) + "^2x" + std::to_string(q.rings) + "x" +
                                  std::to_string(q.layers);
      renderer.renderCloudscape(scene.cloud, q, s);  // warm-up (buffers, shader caches)
      render::RenderStats st;
      const auto t0 = std::chrono::steady_clock::now();
      renderer.renderCloudscape(scene.cloud, q, s, &st);
      const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      char note[256];
      std::snprintf(note, sizeof note, "%zu particles, %zu cells, %zu fragments (%zu overflow, %zu px in more than one chunk)",
                    st.particles, st.validCells, st.fragments, st.fragmentOverflow, st.truncatedPixels);
      const int particles = static_cast<int>(st.particles);
      auto row = [&](const std::string& stage, double seconds, const std::string& r, const std::string& n) {
        report.add(BenchRow{"render", method, stage, variant, r, "", particles, 0, seconds, -1, -1, -1, -1, n});
      };
      row("generation", st.generateSeconds, res, note);
      if (blend == render::BlendMode::Alpha) {
        // The CPU generation of every particle around the camera (render --dump-particles).
        const auto c0 = std::chrono::steady_clock::now();
        const scene::CpuGeneration all = scene::generateCloudscapeAround(scene.cloud, q, view.camera.eye);
        const double cpu = std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
        report.add(BenchRow{"render", "cpu", "generation (all around the camera)", variant, "-", "",
                            static_cast<int>(all.particles.size()), 0, cpu, -1, -1, -1, -1,
                            "scene::generateCloudscapeAround, one thread, no frustum culling"});
      }
      row("sunlight", st.occlusionSeconds, res, "sun volume (cloud lighting, docs/LIGHTING.md)");
      row("shading+blending", st.renderSeconds, res,
          blend == render::BlendMode::Volume ? "draw + resolve (resolve " +
                                                   std::to_string(static_cast<int>(1e3 * st.resolveSeconds)) + " ms)"
                                             : "draw (GPU bitonic sort is in generation)");
      row("total", total, res, "incl. read-back " + std::to_string(static_cast<int>(1e3 * st.readbackSeconds)) + " ms");
      // The seed's lighting (per-particle occlusion, no sun volume), in the same run.
      {
        render::RenderSettings seed = s;
        seed.lighting = render::LightingModel::Seed;
        seed.sunlight = render::defaultSunlight(seed.lighting);
        render::RenderStats ss;
        const auto ts = std::chrono::steady_clock::now();
        renderer.renderCloudscape(scene.cloud, q, seed, &ss);
        const double totalSeed = std::chrono::duration<double>(std::chrono::steady_clock::now() - ts).count();
        const auto seedRow = [&](const std::string& stage, double seconds, const std::string& n) {
          report.add(BenchRow{"render", method + "-seed", stage, variant, res, "", particles, 0, seconds, -1, -1, -1, -1, n});
        };
        char ratio[96];
        std::snprintf(ratio, sizeof ratio, "seed lighting; cloud/seed total time %.2f", total / std::max(totalSeed, 1e-9));
        seedRow("sunlight", ss.occlusionSeconds, "light tiles: lightTilesFor(N) per side, xi 0.05, smoothing");
        seedRow("shading+blending", ss.renderSeconds, "seed lighting");
        seedRow("total", totalSeed, ratio);
      }
      // Half-resolution particles + bilateral upscale (the seed's setting).
      render::RenderSettings half = s;
      half.downscale = 2;
      render::RenderStats sh;
      const auto t1 = std::chrono::steady_clock::now();
      renderer.renderCloudscape(scene.cloud, q, half, &sh);
      const double totalHalf = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
      row("shading+blending", sh.renderSeconds, res + "/2", "particles at half resolution");
      row("upscale", sh.upscaleSeconds, res + "/2", "bilateral (depth-aware), compute shader");
      row("total", totalHalf, res + "/2", "");
      // The seed's Table 1 configuration: 1920×1080, particles at half resolution (volume blending
      // tiles its node pool: render/VolumeResolve.h), as a ratio against the 640×360 ½ case.
      if (!options.quick) {
        render::RenderSettings table1 = s;
        table1.width = 1920;
        table1.height = 1080;
        table1.downscale = 2;
        render::RenderStats st1;
        const auto t2 = std::chrono::steady_clock::now();
        renderer.renderCloudscape(scene.cloud, q, table1, &st1);
        const double total1 = std::chrono::duration<double>(std::chrono::steady_clock::now() - t2).count();
        char ratio[160];
        std::snprintf(ratio, sizeof ratio, "seed Table 1; total / total at %s/2 %.2f; %zu volume tiles, %zu overflow",
                      res.c_str(), total1 / std::max(totalHalf, 1e-9), st1.volumeTiles, st1.fragmentOverflow);
        row("generation", st1.generateSeconds, "1920x1080/2", "seed Table 1");
        row("sunlight", st1.occlusionSeconds, "1920x1080/2", "seed Table 1");
        row("shading+blending", st1.renderSeconds, "1920x1080/2",
            "seed Table 1 (resolve " + std::to_string(static_cast<int>(1e3 * st1.resolveSeconds)) + " ms)");
        row("upscale", st1.upscaleSeconds, "1920x1080/2", "seed Table 1, compute shader");
        row("total", total1, "1920x1080/2", ratio);
      }

      // Temporal stability: a slow forward move with a slight yaw.
      std::vector<double> means;
      ErrorStats worst;
      render::Image previous;
      for (int f = 0; f < frames; ++f) {
        render::RenderSettings m = s;
        m.view.camera = scene::cameraOnPath(view.camera, f, 15.0f, 0.05f);
        render::Image image = renderer.renderCloudscape(scene.cloud, q, m);
        if (f > 0) {
          const ErrorStats e = frameChange(previous, image, view.lighting.skyColor);
          means.push_back(e.mean);
          worst.p95 = std::max(worst.p95, e.p95);
          worst.max = std::max(worst.max, e.max);
        }
        previous = std::move(image);
      }
      double mean = 0;
      for (double v : means) mean += v / static_cast<double>(means.size());
      report.add(BenchRow{"render", method, "stability", variant, res, "", particles, 0, 0.0, mean, worst.p95, worst.max, -1,
                          "mean |frame-to-frame change| of composited radiance, " + std::to_string(frames) +
                              " frames, 15 m + 0.05 deg yaw per frame"});
    }
  }
  benchParticleCount(report, options, renderer);
  reportProgress(options.progress, "bench: render", 1.0);
}

void benchRenderParticleCount(BenchReport& report, const BenchOptions& options) {
  const io::LutSet luts = renderBenchLuts();
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  render::Renderer renderer(*context, luts);
  benchParticleCount(report, options, renderer);
}

}  // namespace cloudlut::bench
