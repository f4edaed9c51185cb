// The ground-truth suite of `cloudlut bench`: every rendering method on the scenes of
// data/bench_scenes, timed, and judged against the path-traced ground truth of the same medium
// (reference/ScenePathTracer.h) with the metrics of reference/SceneCompare.h.
//
// Rows: method "path-traced" (the reference itself: seconds, and in error_mean the RMS of its
// per-pixel standard error over the cloud pixels, i.e. its noise floor), "lut-alpha" and "lut-volume" (the
// particle renderer from tables baked at reduced resolution, alpha or volume-aware blending,
// with the cloud lighting model; "-seed" appended: the seed's model; "-18" appended: 18-order
// instead of converged multiple scattering), "raymarch" and
// "raymarch-adaptive" at several step counts. error_mean = RMSE of R, G, B over the cloud
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

#include "bake/OpticalDepthBaker.h"
#include "bake/ScatteringBaker.h"
#include "bench/BenchSuites.h"
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

constexpr int kWidth = 96, kHeight = 64;
const char* const kScenes[] = {"one",   "one-rho1", "one-rho4",  "backlit",   "two",
                               "three", "cluster",  "cluster36", "cloudscape"};

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
    const bake::ScatteringResult r = bake::bakeScattering(sc);
    if (!r.single || !r.multiple) throw std::runtime_error("the scattering baker returned no tables");
    nlohmann::json entries = nlohmann::json::object();
    for (const Table4D* t : {&depth, &*r.single, &*r.multiple})
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

std::string noteOf(const reference::ImageErrors& e) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "rel_rmse=%.4f nc_rel_rmse=%.4f rel_bias=%+.4f ssim=%.4f alpha_rmse=%.3g",
                e.relativeRmse, e.noiseCorrectedRelativeRmse, e.relativeBias, e.ssim, e.alphaRmse);
  return buf;
}

}  // namespace

void benchGroundTruth(BenchReport& report, const BenchOptions& options, const fs::path& out) {
  const fs::path sceneDir = findSceneDir();
  const fs::path cache = out / "ground-truth";
  fs::create_directories(cache);
  const int spp = options.quick ? 256 : 1024;
  const int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(std::max(threads, 1)));

  const Medium medium;  // the defaults (core/Defaults.h): noise model, seed 1, β, R, CS g 0.9 then 0.7
  std::string lutNote;
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  // Two LUT sets: converged and 18-order multiple scattering. One cache per format version:
  // tables of an older version are not re-read (re-baked instead).
  struct LutRenderer {
    std::string suffix;
    std::unique_ptr<io::LutSet> luts;
    std::unique_ptr<render::Renderer> renderer;
  };
  std::vector<LutRenderer> lutRenderers;
  for (const int orders : {0, 18}) {
    const std::string tag = orders == 0 ? "" : "-" + std::to_string(orders);
    const fs::path lutDir = cache / ("luts-v" + std::to_string(io::kFormatVersion) + tag + (options.quick ? "-quick" : "-default"));
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
    const std::string name = kScenes[si];
    const fs::path sceneFile = sceneDir / (name + ".json");
    const scene::Scene scene = scene::readScene(sceneFile);
    const scene::View view = scene::resolveView(scene, {});

    // The reference, cached by a hash of everything it depends on.
    reference::ScenePtSettings st;
    st.samplesPerPixel = spp;
    st.seed = 1;
    const std::string key = readText(sceneFile) + "|" + toString(medium.model) + "|" + std::to_string(medium.seed) + "|" +
                            std::to_string(medium.unitOpticalRadius()) + "|" + std::to_string(spp) + "|" +
                            std::to_string(kWidth) + "x" + std::to_string(kHeight) + "|v1";
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
      ref = reference::renderReferenceScene(scene.particles, view, medium, st, kWidth, kHeight, progress, &stats);
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
    BenchRow refRow;
    refRow.suite = "ground-truth";
    refRow.method = "path-traced";
    refRow.table = name;
    refRow.variant = toString(medium.model);
    refRow.resolution = std::to_string(kWidth) + "x" + std::to_string(kHeight);
    refRow.steps = spp;
    refRow.threads = threads;
    refRow.seconds = refSeconds;
    refRow.errorMean = noise;
    refRow.note = std::string("reference; error_mean = RMS standard error (noise floor)") + (cached ? "; cached" : "");
    report.add(refRow);

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
        for (const render::BlendMode blend : {render::BlendMode::Alpha, render::BlendMode::Volume}) {
          render::RenderSettings rs;
          rs.width = kWidth;
          rs.height = kHeight;
          rs.view = view;
          rs.blend = blend;
          rs.lighting = lighting;
          rs.sunlight = render::defaultSunlight(lighting);
          render::Image img;
          const double t =
              best([&](render::RenderStats* s) { return lr.renderer->render(scene.particles, rs, s); }, img);
          const std::string method = std::string(blend == render::BlendMode::Alpha ? "lut-alpha" : "lut-volume") +
                                     (lighting == render::LightingModel::Seed ? "-seed" : "") + lr.suffix;
          addRow(method, 0, img, t,
                 std::string("; lighting ") + toString(lighting) + ", sunlight " + toString(rs.sunlight) + ", tables " +
                     lr.luts->tables.at("multiple_scattering").table.name() +
                     (lr.suffix.empty() ? " converged" : " 18 orders") + ", reduced resolution");
        }
    for (const bool adaptive : {false, true})
      for (const int n : steps) {
        render::RayMarchSettings rm;
        rm.width = kWidth;
        rm.height = kHeight;
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
