// `cloudlut render --method raymarch`: the ray-marched baseline (render/RayMarchRenderer.h) of
// a particle scene, the medium from --luts' manifest or the medium options, into a PNG or an
// EXR. Dispatched from RenderCommand.cpp after its options are parsed.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli/Options.h"
#include "cli/SceneOptions.h"
#include "core/Errors.h"
#include "render/GlContext.h"
#include "render/ImageWriters.h"
#include "render/RayMarchRenderer.h"

namespace cloudlut::cli {

int runRayMarchRender(const cxxopts::ParseResult& args) {
  for (const char* required : {"particles", "out"})
    if (!args.count(required)) throw UsageError(std::string("missing --") + required);
  if (args.count("detail-noise") && args["detail-noise"].as<std::string>() != "off")
    throw UsageError("--detail-noise applies to --method particles (the ray marcher has no detail noise)");
  const std::filesystem::path out = args["out"].as<std::string>();
  std::string ext = out.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".png" && ext != ".exr") throw UsageError("--out: expected a .png or .exr file name, got '" + out.string() + "'");
  const long long width = args["width"].as<long long>(), height = args["height"].as<long long>();
  render::checkImageSize(width, height);
  const double exposure = requirePositive(args["exposure"].as<double>(), "exposure");

  render::RayMarchSettings s;
  s.width = static_cast<int>(width);
  s.height = static_cast<int>(height);
  s.terms = parseTermList(args["terms"].as<std::string>());
  s.steps = args["steps"].as<int>();
  s.adaptive = args.count("adaptive") > 0;
  s.shadowSteps = args["shadow-steps"].as<int>();
  s.octaves = args["octaves"].as<int>();
  const glm::vec3 abc = parseVec3Option(args["octave-abc"].as<std::string>(), "octave-abc", true);
  s.a = abc.x;
  s.b = abc.y;
  s.c = abc.z;
  const Medium medium = parseMedium(args);
  s.first = medium.first;
  s.later = medium.later;
  s.unitOpticalRadius = static_cast<float>(medium.unitOpticalRadius());
  scene::ViewSettings overrides = parseViewOverrides(args);
  overrides.atmosphere = parseSkyModel(args);
  const scene::Scene scene = scene::readScene(args["particles"].as<std::string>());
  scene::checkRenderParticleCount(scene.particles.size(), args["particles"].as<std::string>(),
                                  scene::kMaxRayMarchParticles, "raymarch");
  s.view = scene::resolveView(scene, overrides);
  requireUniformSky(s.view, args, args["particles"].as<std::string>(), "ray marcher");

  const auto t0 = std::chrono::steady_clock::now();
  const ReferenceParticle particle(medium.model, medium.seed);
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  render::RayMarchRenderer marcher(*context, particle);
  const double setup = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  render::RenderStats stats;
  const render::Image image = marcher.render(scene.particles, s, &stats);
  if (const std::size_t bad = image.nonFiniteCount())
    throw std::runtime_error("the ray-marched image holds " + std::to_string(bad) + " non-finite values");
  if (ext == ".png") render::writePng(image, out, s.view.lighting.skyColor, static_cast<float>(exposure));
  else render::writeExr(image, out);
  if (!args.count("quiet"))
    std::printf("wrote %s: %dx%d, %zu particles, raymarch %d steps%s, render %.1f ms (setup %.1f ms, %s)\n", out.c_str(),
                image.width, image.height, scene.particles.size(), s.steps, s.adaptive ? " adaptive" : "",
                1e3 * stats.renderSeconds, 1e3 * setup, context->description().c_str());
  if (stats.rayMarchDroppedPixels > 0)
    std::fprintf(stderr, "cloudlut render: warning: %zu pixels crossed more than %d particles on the view ray or %d on a shadow ray; the farthest were left out\n",
                 stats.rayMarchDroppedPixels, render::kMaxViewHits, render::kMaxShadowHits);
  if (stats.rayMarchBudgetPixels > 0)
    std::fprintf(stderr, "cloudlut render: warning: the GL cut the loops of %zu pixels short (llvmpipe allows 65535 loop passes per shader invocation); their march is incomplete: use fewer --steps or --shadow-steps\n",
                 stats.rayMarchBudgetPixels);
  return kExitOk;
}

}  // namespace cloudlut::cli
