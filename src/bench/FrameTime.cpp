#include "bench/FrameTime.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <glm/gtc/matrix_transform.hpp>

namespace cloudlut::bench {

namespace {

constexpr int kRayMarchSteps = 32;
constexpr int kTimedFrames = 3;
constexpr float kSunTurnDegrees = 1.0f;  // the moving sun's rows: per frame, about the vertical

// `sun` (unit, toward the sun) turned by `degrees` about the world's vertical (+y).
glm::vec3 turnedSun(const glm::vec3& sun, float degrees) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0.0f, 1.0f, 0.0f)) *
                   glm::vec4(sun, 0.0f));
}

// Best of kTimedFrames after one unmeasured frame; `frame` renders into `image` and returns
// its seconds.
template <typename Frame>
double steadyFrameSeconds(Frame&& frame, render::Image& image) {
  frame(image);
  double best = 1e30;
  for (int k = 0; k < kTimedFrames; ++k) best = std::min(best, frame(image));
  return best;
}

// Relative RMSE of a's RGB against b's over the pixels where either has alpha > 0.01.
double relativeRmse(const render::Image& a, const render::Image& b) {
  double se = 0.0, ref = 0.0;
  for (std::size_t i = 0; i + 3 < a.rgba.size() && i + 3 < b.rgba.size(); i += 4) {
    if (a.rgba[i + 3] <= 0.01f && b.rgba[i + 3] <= 0.01f) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(a.rgba[i + c]) - b.rgba[i + c];
      se += d * d;
      ref += static_cast<double>(b.rgba[i + c]) * b.rgba[i + c];
    }
  }
  return ref > 0.0 ? std::sqrt(se / ref) : 0.0;
}

// The LUT renderer's timed frames: volume blending at width × height, particles at 1/downscale.
render::RenderSettings lutFrameSettings(int width, int height, const scene::View& view, int downscale) {
  render::RenderSettings rs;
  rs.width = width;
  rs.height = height;
  rs.view = view;
  rs.blend = render::BlendMode::Volume;
  rs.downscale = downscale;
  return rs;
}

// steadyFrameSeconds of the LUT renderer's frames of `particles` under `rs` (upload, light-space
// passes, shading, blending, upscale), `beforeFrame(rs)` run before each.
template <typename BeforeFrame>
double lutFrameSeconds(render::Renderer& lut, const std::vector<scene::Particle>& particles,
                       render::RenderSettings& rs, render::Image& image, BeforeFrame&& beforeFrame) {
  return steadyFrameSeconds(
      [&](render::Image& out) {
        beforeFrame(rs);
        render::RenderStats s;
        out = lut.render(particles, rs, &s);
        return s.uploadSeconds + s.occlusionSeconds + s.renderSeconds + s.upscaleSeconds;
      },
      image);
}

// A LUT frame's row: `base` with `method`, steps = the downscale factor and the time; the note
// says what the frame does (`what`), its particle resolution and its speed-up over the ray
// marcher's frame of marchSeconds.
BenchRow lutFrameRow(const BenchRow& base, const char* method, int downscale, double seconds, double marchSeconds,
                     const std::string& what) {
  BenchRow row = base;
  row.method = method;
  row.steps = downscale;
  row.seconds = seconds;
  char tail[160];
  std::snprintf(tail, sizeof tail, ", particles at 1/%d resolution; %.2fx the ray marcher's %d-step frame", downscale,
                marchSeconds / std::max(seconds, 1e-9), kRayMarchSteps);
  row.note = what + tail;
  return row;
}

}  // namespace

std::vector<BenchRow> frameTimeRows(const std::string& sceneName, const scene::Scene& scene, const scene::View& view,
                                    render::Renderer& lut, render::RayMarchRenderer& marcher,
                                    const render::RayMarchSettings& marchBase, bool quick) {
  const int width = quick ? 640 : 1280, height = quick ? 360 : 720;
  BenchRow base;
  base.suite = "ground-truth";
  base.table = sceneName;
  base.resolution = std::to_string(width) + "x" + std::to_string(height);

  render::RayMarchSettings rm = marchBase;
  rm.width = width;
  rm.height = height;
  rm.view = view;
  rm.steps = kRayMarchSteps;
  render::Image marched;
  const double marchSeconds = steadyFrameSeconds(
      [&](render::Image& img) {
        render::RenderStats s;
        img = marcher.render(scene.particles, rm, &s);
        return s.uploadSeconds + s.renderSeconds;
      },
      marched);
  std::vector<BenchRow> rows;
  BenchRow marchRow = base;
  marchRow.method = "frame-raymarch";
  marchRow.steps = kRayMarchSteps;
  marchRow.seconds = marchSeconds;
  marchRow.note = "steady-state frame (upload, march), best of 3 after one";
  rows.push_back(marchRow);

  // The cold frames build the light-space volumes every frame; the kept ones reuse the first
  // frame's (RenderSettings::keepLighting: still clouds, still sun).
  render::Image full;
  for (const bool keep : {false, true})
    for (const int downscale : {1, 2, 4}) {
      render::RenderSettings rs = lutFrameSettings(width, height, view, downscale);
      rs.keepLighting = keep;
      render::Image img;
      const double seconds = lutFrameSeconds(lut, scene.particles, rs, img, [](render::RenderSettings&) {});
      if (downscale == 1 && !keep) full = img;
      BenchRow row = lutFrameRow(base, keep ? "frame-lut-volume-kept" : "frame-lut-volume", downscale, seconds,
                                 marchSeconds,
                                 std::string("steady-state frame (upload, ") +
                                     (keep ? "light-space volumes kept from the frame before" : "light-space passes") +
                                     ", shading, blending, upscale)");
      if (downscale > 1 || keep) row.errorMean = relativeRmse(img, full);
      rows.push_back(row);
    }

  // The sun turning kSunTurnDegrees about the vertical every frame, the lighting kept
  // (RenderSettings::keepLighting): the sun volume built again, the zenith and diffusion column
  // volumes kept, the diffusion solve warm-started (LightSpaceInputs.h, reusableUnderMovedSun).
  // Against a cold full-resolution frame under the last frame's sun.
  for (const int downscale : {1, 2, 4}) {
    render::RenderSettings rs = lutFrameSettings(width, height, view, downscale);
    int turns = 0;
    render::Image img;
    const double seconds = lutFrameSeconds(lut, scene.particles, rs, img, [&](render::RenderSettings& next) {
      ++turns;
      next.view.lighting.sunDirection =
          turnedSun(view.lighting.sunDirection, kSunTurnDegrees * static_cast<float>(turns));
    });
    render::RenderSettings cold = rs;
    cold.downscale = 1;
    cold.keepLighting = false;
    const render::Image reference = lut.render(scene.particles, cold);
    char what[160];
    std::snprintf(what, sizeof what,
                  "steady-state frame under a sun turning %.0f deg a frame (the sun volume built again, the "
                  "diffusion solve warm-started)",
                  static_cast<double>(kSunTurnDegrees));
    BenchRow row = lutFrameRow(base, "frame-lut-volume-sun", downscale, seconds, marchSeconds, what);
    row.errorMean = relativeRmse(img, reference);
    rows.push_back(row);
  }

  // The seed's model (seed §4.4, §5.3: sunlight per particle from the light-space tile occlusion,
  // LM(ρ), the crease ambient), the same blending and resolutions: what the cloud model's terms
  // cost on top of it. Its only light-space pass, the occlusion, runs every frame.
  render::Image seedFull;
  for (const int downscale : {1, 2, 4}) {
    render::RenderSettings rs = lutFrameSettings(width, height, view, downscale);
    rs.lighting = render::LightingModel::Seed;
    rs.sunlight = render::defaultSunlight(rs.lighting);
    render::Image img;
    const double seconds = lutFrameSeconds(lut, scene.particles, rs, img, [](render::RenderSettings&) {});
    if (downscale == 1) seedFull = img;
    BenchRow row = lutFrameRow(base, "frame-lut-volume-seed", downscale, seconds, marchSeconds,
                               "steady-state frame with the seed's lighting model (tile occlusion, LM(rho), crease "
                               "ambient)");
    if (downscale > 1) row.errorMean = relativeRmse(img, seedFull);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace cloudlut::bench
