// The ground-truth suite of `cloudlut bench`: every rendering method on the scenes of
// data/bench_scenes, timed, and judged against the path-traced ground truth of the same medium
// (reference/ScenePathTracer.h) with the metrics of reference/SceneCompare.h.
//
// Rows: method "path-traced" (the reference itself: seconds, and in error_mean the RMS of its
// per-pixel standard error over the cloud pixels, i.e. its noise floor), "lut-alpha" and "lut-volume" (the
// particle renderer from tables baked at reduced resolution, alpha or volume-aware blending,
// with the cloud lighting model; "-seed" appended: the seed's model; "-tables": the cloud model
// without the diffusion volume (docs/LIGHTING.md); "-18" appended: 18-order
// instead of converged multiple scattering), "raymarch" and
// "raymarch-adaptive" at several step counts; and the steady-state frame times of
// bench/FrameTime.h ("frame-lut-volume", "frame-raymarch", at 1280×720), with the accuracy of
// those frames' renderer at about their size ("frame-lut-volume-accuracy", steps = the particles'
// downscale; no time). error_mean = RMSE of R, G, B over the cloud
// pixels, error_p95 = 95th percentile of the per-pixel |error| (mean of the channels),
// error_max = largest error; the note holds the relative RMSE, the relative RMSE with the
// reference's noise removed (nc_rel_rmse), the relative bias and SSIM. Times are the
// best of three renders (GPU draw + finish, llvmpipe on this machine), not counting set-up.
//
// Caches under OUT/ground-truth: the reference EXRs (keyed by a hash of the scene file and every
// setting) and the LUT set, so that re-runs only render the methods.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include <unistd.h>

#include <tbb/global_control.h>

#include "bake/AngularClosureBaker.h"
#include "bake/OpticalDepthBaker.h"
#include "bake/ScatteringBaker.h"
#include "bench/BenchSuites.h"
#include "bench/FrameTime.h"
#include "core/Medium.h"
#include "core/Errors.h"
#include "io/Fnv1a.h"
#include "io/LutIo.h"
#include "io/ManifestSchema.h"
#include "reference/ReferenceImage.h"
#include "reference/SceneCompare.h"
#include "render/GlContext.h"
#include "render/RayMarchRenderer.h"
#include "render/Renderer.h"

namespace cloudlut::bench {
namespace {

namespace fs = std::filesystem;

// The scenes of data/bench_scenes, each with its image size and the reference's paths per pixel
// (full, --quick). The 1419-particle cloudscape patch is path traced at 45×30: 1536 paths per
// pixel keep its noise under a third of the cloud model's error (at 512 it was half), and its
// reference takes ~10 min on one core (the BVH of reference/ParticleBvh.h makes it possible).
struct BenchScene {
  const char* name;
  int width, height;
  int spp, sppQuick;
};
const BenchScene kScenes[] = {
    {"one", 96, 64, 1024, 256},       {"one-rho1", 96, 64, 1024, 256},  {"one-rho4", 96, 64, 1024, 256},
    {"backlit", 96, 64, 1024, 256},   {"two", 96, 64, 1024, 256},       {"three", 96, 64, 1024, 256},
    {"cluster", 96, 64, 1024, 256},   {"cluster36", 96, 64, 1024, 256}, {"cloudscape", 96, 64, 1024, 256},
    {"cloudscape-patch", 45, 30, 1536, 256},
};

fs::path findSceneDir() {
  std::vector<fs::path> candidates = {fs::current_path() / "data" / "bench_scenes"};
  char exe[4096];
  const ssize_t n = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    exe[n] = '\0';
    fs::path p = fs::path(exe).parent_path();
    for (int up = 0; up < 4 && !p.empty(); ++up, p = p.parent_path()) candidates.push_back(p / "data" / "bench_scenes");
  }
  for (const auto& c : candidates)
    if (fs::exists(c / "one.json")) return c;
  throw UsageError("bench ground-truth: cannot find data/bench_scenes (run from the source tree)");
}

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string hex(std::uint64_t v) {
  char buf[20];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// The LUT set the particle renderer uses: optical depth of the medium's model and the default
// scattering tables (converged or 18-order multiple scattering), as a user's bake gives them;
// reduced resolution with --quick; cached in `dir`.
bool ensureLutSet(const fs::path& dir, const Medium& medium, bool quick, int orders, std::string& note) {
  if (fs::exists(dir / "manifest.json")) return true;
  try {
    fs::create_directories(dir);
    bake::OpticalDepthSettings od;
    od.dims = quick ? std::array<int, 4>{32, 16, 32, 16} : defaults::kOpticalDepthDims;
    const Table4D depth = bake::bakeOpticalDepth(ReferenceParticle(medium.model, medium.seed), od);
    bake::ScatteringSettings sc;
    if (quick) sc.dims = {16, 32, 8, 8};
    sc.orders = orders;  // 0: converged
    bake::ScatteringResult r = bake::bakeScattering(sc);
    if (!r.single || !r.multiple) throw std::runtime_error("the scattering baker returned no tables");
    // the multiple table's angular closure, as `cloudlut bake` attaches it (bake/AngularClosure.h)
    bake::AngularClosureSettings closure;
    if (quick) closure.photonsPerDirection = 2000;
    bake::attachAngularClosure(*r.multiple, depth, ReferenceParticle(medium.model, medium.seed), sc.firstPhase,
                               sc.laterPhase, closure);
    nlohmann::json entries = nlohmann::json::object();
    for (const Table4D* t : {&depth, static_cast<const Table4D*>(&*r.single), static_cast<const Table4D*>(&*r.multiple)})
      entries[t->name()] = io::writeTableFiles(*t, io::SampleType::Float, dir, {.bin = true, .exr = false});
    io::writeManifest(dir, io::makeManifest("cloudlut bench ground-truth", entries));
    return true;
  } catch (const std::exception& e) {
    note = std::string("LUT set not available: ") + e.what();
    std::error_code ec;
    fs::remove_all(dir, ec);
    return false;
  }
}

// The odd factor F that brings `height` rows closest to the frames' 720 from below (at least 1):
// the centre of an F × F block of sub-pixels is the centre of the pixel it makes.
int frameSizeFactor(int height) {
  int f = std::max(1, 720 / std::max(height, 1));
  return f % 2 == 1 ? f : f - 1;
}

// The image of the sub-pixels at the centres of the factor × factor blocks of `fine`.
render::Image blockCentres(const render::Image& fine, int factor) {
  render::Image out;
  out.width = fine.width / factor;
  out.height = fine.height / factor;
  out.rgba.resize(static_cast<std::size_t>(out.width) * out.height * 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const float* p = fine.pixel(x * factor + factor / 2, y * factor + factor / 2);
      std::copy(p, p + 4, out.rgba.begin() + 4 * (static_cast<std::ptrdiff_t>(y) * out.width + x));
    }
  return out;
}

struct Errors {
  reference::ImageErrors e;
  double p95 = 0;
};

Errors judge(const render::Image& img, const io::ExrImage& ref) {
  Errors out;
  out.e = reference::compareToReference(img.width, img.height, img.rgba.data(), ref);
  // 95th percentile of the per-pixel |error| (mean of R, G, B) over the same cloud pixels
  const std::vector<float>&r = ref.channel("R"), &g = ref.channel("G"), &b = ref.channel("B"), &a = ref.channel("A");
  std::vector<double> pixel;
  for (std::size_t i = 0; i < ref.pixelCount(); ++i) {
    const float* p = &img.rgba[4 * i];
    if (p[3] > reference::kDefaultAlphaThreshold || a[i] > reference::kDefaultAlphaThreshold)
      pixel.push_back((std::abs(p[0] - r[i]) + std::abs(p[1] - g[i]) + std::abs(p[2] - b[i])) / 3.0);
  }
  if (!pixel.empty()) {
    std::sort(pixel.begin(), pixel.end());
    out.p95 = pixel[std::min(pixel.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(pixel.size())))];
  }
  return out;
}

// A ground-truth row of the path tracer `method` on scene `name`: its image size and paths per
// pixel; seconds, errors and note are the caller's.
BenchRow pathTracedRow(const std::string& method, const std::string& name, const Medium& medium, int width, int height,
                       int spp, int threads) {
  BenchRow row;
  row.suite = "ground-truth";
  row.method = method;
  row.table = name;
  row.variant = toString(medium.model);
  row.resolution = std::to_string(width) + "x" + std::to_string(height);
  row.steps = spp;
  row.threads = threads;
  return row;
}

// The path tracer's BVH against its brute-force loop (ScenePtSettings::bruteForce) on one scene:
// a small image (24×16, 4 paths per pixel) both ways on the same threads, seconds of each and
// whether the two images are the same bit for bit.
BenchRow bvhSpeedRow(const std::string& name, const scene::Scene& scene, const scene::View& view, const Medium& medium,
                     int threads) {
  constexpr int w = 24, h = 16;
  reference::ScenePtSettings st;
  st.samplesPerPixel = 4;
  double seconds[2] = {0, 0};
  io::ExrImage img[2];
  for (int k = 0; k < 2; ++k) {
    st.bruteForce = k == 1;
    reference::ReferenceSceneStats stats;
    img[k] = reference::renderReferenceScene(scene.particles, view, medium, st, w, h, {}, &stats);
    seconds[k] = stats.seconds;
  }
  bool same = true;
  for (const char* c : {"R", "G", "B", "A"}) same = same && img[0].channel(c) == img[1].channel(c);
  BenchRow row = pathTracedRow("path-traced-brute-force", name, medium, w, h, st.samplesPerPixel, threads);
  row.seconds = seconds[1];
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "every particle per ray; with the BVH %.3f s, speed-up %.2fx; images %s bit for bit (%zu particles)",
                seconds[0], seconds[1] / std::max(seconds[0], 1e-9), same ? "equal" : "DIFFERENT",
                scene.particles.size());
  row.note = buf;
  return row;
}

std::string noteOf(const reference::ImageErrors& e) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "rel_rmse=%.4f nc_rel_rmse=%.4f rel_bias=%+.4f ssim=%.4f alpha_rmse=%.3g",
                e.relativeRmse, e.noiseCorrectedRelativeRmse, e.relativeBias, e.ssim, e.alphaRmse);
  return buf;
}

}  // namespace

void benchGroundTruth(BenchReport& report, const BenchOptions& options, const fs::path& out) {
  std::string known;
  for (const BenchScene& s : kScenes) known += std::string(known.empty() ? "" : ", ") + s.name;
  for (const std::string& name : options.scenes)
    if (std::none_of(std::begin(kScenes), std::end(kScenes), [&](const BenchScene& s) { return name == s.name; }))
      throw UsageError("--scenes: unknown ground-truth scene '" + name + "' (" + known + ")");
  const auto selected = [&](const std::string& name) {
    return options.scenes.empty() || std::find(options.scenes.begin(), options.scenes.end(), name) != options.scenes.end();
  };
  const fs::path sceneDir = findSceneDir();
  const fs::path cache = out / "ground-truth";
  fs::create_directories(cache);
  const int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(std::max(threads, 1)));

  const Medium medium;  // the defaults (core/Defaults.h): noise model, seed 1, β, R, CS g 0.9 then 0.7
  std::string lutNote;
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  // Two LUT sets: converged and 18-order multiple scattering. One cache per format version and
  // per change to what the bake writes (the closure's core shadow, the chords' outer-third
  // share): tables baked before are not re-read (re-baked instead).
  struct LutRenderer {
    std::string suffix;
    std::unique_ptr<io::LutSet> luts;
    std::unique_ptr<render::Renderer> renderer;
  };
  std::vector<LutRenderer> lutRenderers;
  for (const int orders : {0, 18}) {
    const std::string tag = orders == 0 ? "" : "-" + std::to_string(orders);
    const fs::path lutDir = cache / ("luts-v" + std::to_string(io::kFormatVersion) + tag + (options.quick ? "-quick" : "-default") + "-closure-core-shadow-1.2-chord-thirds");
    reportProgress(options.progress, "ground-truth: LUT set" + tag, 0.0);
    if (!ensureLutSet(lutDir, medium, options.quick, orders, lutNote)) continue;
    try {
      LutRenderer lr{tag, std::make_unique<io::LutSet>(io::readLutSet(lutDir)), nullptr};
      lr.renderer = std::make_unique<render::Renderer>(*context, *lr.luts);
      lutRenderers.push_back(std::move(lr));
    } catch (const std::exception& e) {
      lutNote = std::string("LUT renderer not available: ") + e.what();
    }
  }
  const ReferenceParticle particle(medium.model, medium.seed);

  render::RayMarchRenderer marcher(*context, particle);
  const std::vector<int> steps = options.quick ? std::vector<int>{8, 32, 128} : std::vector<int>{4, 8, 16, 32, 64, 128, 256};

  const int sceneCount = static_cast<int>(std::size(kScenes));
  for (int si = 0; si < sceneCount; ++si) {
    const std::string name = kScenes[si].name;
    if (!selected(name)) continue;
    const int width = kScenes[si].width, height = kScenes[si].height;
    const int spp = options.quick ? kScenes[si].sppQuick : kScenes[si].spp;
    const fs::path sceneFile = sceneDir / (name + ".json");
    const scene::Scene scene = scene::readScene(sceneFile);
    const scene::View view = scene::resolveView(scene, {});

    // The reference, cached by a hash of everything it depends on.
    reference::ScenePtSettings st;
    st.samplesPerPixel = spp;
    st.seed = 1;
    const std::string key = readText(sceneFile) + "|" + toString(medium.model) + "|" + std::to_string(medium.seed) + "|" +
                            std::to_string(medium.unitOpticalRadius()) + "|" + std::to_string(spp) + "|" +
                            std::to_string(width) + "x" + std::to_string(height) + "|v1";
    const fs::path refPath = cache / ("reference-" + name + "-" + hex(io::fnv1a64(key)) + ".exr");
    io::ExrImage ref;
    double refSeconds = -1;
    bool cached = false;
    if (fs::exists(refPath)) {
      ref = io::readExrImage(refPath);
      cached = true;
      if (ref.attributes.count("cloudlutSeconds")) refSeconds = std::stod(ref.attributes["cloudlutSeconds"]);
    } else {
      reference::ReferenceSceneStats stats;
      const ProgressFn progress = [&](std::string_view, double f) {
        reportProgress(options.progress, "ground-truth: " + name, f);
      };
      ref = reference::renderReferenceScene(scene.particles, view, medium, st, width, height, progress, &stats);
      refSeconds = stats.seconds;
      ref.attributes["cloudlutSeconds"] = std::to_string(stats.seconds);
      io::writeExrImage(ref, refPath);
    }
    // Noise floor: RMS standard error of R, G, B over the cloud pixels.
    double se2 = 0;
    std::size_t cloud = 0;
    for (std::size_t i = 0; i < ref.pixelCount(); ++i) {
      if (ref.channel("A")[i] <= reference::kDefaultAlphaThreshold) continue;
      ++cloud;
      for (const char* c : {"stderr.R", "stderr.G", "stderr.B"}) se2 += ref.channel(c)[i] * ref.channel(c)[i];
    }
    const double noise = cloud ? std::sqrt(se2 / (3.0 * static_cast<double>(cloud))) : 0.0;
    BenchRow refRow = pathTracedRow("path-traced", name, medium, width, height, spp, threads);
    refRow.seconds = refSeconds;
    refRow.errorMean = noise;
    refRow.note = std::string("reference; error_mean = RMS standard error (noise floor)") + (cached ? "; cached" : "");
    report.add(refRow);
    if (name == "cloudscape-patch") report.add(bvhSpeedRow(name, scene, view, medium, threads));

    auto addRow = [&](const std::string& method, int stepCount, const render::Image& img, double seconds,
                      const std::string& extra) {
      const Errors e = judge(img, ref);
      BenchRow row = refRow;
      row.method = method;
      row.steps = stepCount;
      row.threads = 0;
      row.seconds = seconds;
      row.errorMean = e.e.rmse;
      row.errorP95 = e.p95;
      row.errorMax = e.e.maxError;
      row.note = noteOf(e.e) + extra;
      report.add(row);
    };
    auto best = [](auto&& renderOnce, render::Image& img) {
      double t = 1e30;
      for (int k = 0; k < 3; ++k) {
        render::RenderStats stats;
        img = renderOnce(&stats);
        t = std::min(t, stats.renderSeconds);
      }
      return t;
    };

    for (const LutRenderer& lr : lutRenderers)
      for (const render::LightingModel lighting : {render::LightingModel::Cloud, render::LightingModel::Seed})
        for (const render::BlendMode blend : {render::BlendMode::Alpha, render::BlendMode::Volume})
          for (const bool diffusion : {true, false}) {
            // the cloud model without the diffusion volume ("-tables"): volume blending only
            if (!diffusion && (lighting != render::LightingModel::Cloud || blend != render::BlendMode::Volume)) continue;
            render::RenderSettings rs;
            rs.width = width;
            rs.height = height;
            rs.view = view;
            rs.blend = blend;
            rs.lighting = lighting;
            rs.sunlight = render::defaultSunlight(lighting);
            if (!diffusion) rs.diffusionShare = 0.0f;
            render::Image img;
            const double t =
                best([&](render::RenderStats* s) { return lr.renderer->render(scene.particles, rs, s); }, img);
            const std::string method = std::string(blend == render::BlendMode::Alpha ? "lut-alpha" : "lut-volume") +
                                       (lighting == render::LightingModel::Seed ? "-seed" : "") +
                                       (diffusion ? "" : "-tables") + lr.suffix;
            addRow(method, 0, img, t,
                   std::string("; lighting ") + toString(lighting) + ", sunlight " + toString(rs.sunlight) +
                       (lighting == render::LightingModel::Cloud ? (diffusion ? ", diffusion" : ", no diffusion") : "") +
                       ", tables " + lr.luts->tables.at("multiple_scattering").table.name() +
                       (lr.suffix.empty() ? " converged" : " 18 orders") + ", reduced resolution");
          }
    // The speed goal's reduced resolutions judged against the path tracer: the default renderer
    // (converged tables) at about the frames' 720 rows, an odd factor F times the reference's
    // size, the particles at 1/1, 1/2 and 1/4 of it and upscaled; the sub-pixel at the centre of
    // each F × F block lies on the reference pixel's centre ray, which the path tracer samples.
    const int factor = frameSizeFactor(height);
    if (!lutRenderers.empty() && lutRenderers.front().suffix.empty())
      for (const int downscale : {1, 2, 4}) {
        render::RenderSettings rs;
        rs.width = width * factor;
        rs.height = height * factor;
        rs.view = view;
        rs.blend = render::BlendMode::Volume;
        rs.downscale = downscale;
        const render::Image frame = lutRenderers.front().renderer->render(scene.particles, rs);
        addRow("frame-lut-volume-accuracy", downscale, blockCentres(frame, factor), 0.0,
               "; the default renderer at " + std::to_string(rs.width) + "x" + std::to_string(rs.height) +
                   ", particles at 1/" + std::to_string(downscale) + ", judged at the reference's pixel centres");
      }
    for (const bool adaptive : {false, true})
      for (const int n : steps) {
        render::RayMarchSettings rm;
        rm.width = width;
        rm.height = height;
        rm.view = view;
        rm.steps = n;
        rm.adaptive = adaptive;
        rm.first = medium.first;
        rm.later = medium.later;
        rm.unitOpticalRadius = static_cast<float>(medium.unitOpticalRadius());
        render::Image img;
        const double t = best([&](render::RenderStats* s) { return marcher.render(scene.particles, rm, s); }, img);
        addRow(adaptive ? "raymarch-adaptive" : "raymarch", n, img, t, "; shadow steps 6, octaves 8, abc 0.5");
      }
    // Issue 17's speed goal: steady-state frames at 1280×720 (bench/FrameTime.h), converged tables.
    if (!lutRenderers.empty() && lutRenderers.front().suffix.empty()) {
      render::RayMarchSettings rm;
      rm.first = medium.first;
      rm.later = medium.later;
      rm.unitOpticalRadius = static_cast<float>(medium.unitOpticalRadius());
      for (BenchRow& row : frameTimeRows(name, scene, view, *lutRenderers.front().renderer, marcher, rm, options.quick)) {
        row.variant = toString(medium.model);
        report.add(row);
      }
    }
    reportProgress(options.progress, "ground-truth", static_cast<double>(si + 1) / sceneCount);
  }
  if (!lutNote.empty()) {
    BenchRow row;
    row.suite = "ground-truth";
    row.method = "lut-alpha";
    row.note = lutNote;
    report.add(row);
  }
}

}  // namespace cloudlut::bench
