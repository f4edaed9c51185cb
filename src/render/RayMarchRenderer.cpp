#include "render/RayMarchRenderer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/Errors.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/GpuStorage.h"
#include "render/ParticleCellGrid.h"
#include "render/ShaderSources.h"
#include "render/Stopwatch.h"

namespace cloudlut::render {


struct RayMarchRenderer::Impl {
  GlContext& context;
  GlFunctions gl;
  StorageBudget budget;
  GlProgram program;
  StorageBuffer particles;  // GpuParticleRecord at binding 0
  StorageBuffer cellStarts, cellParticles;  // the particle cell grid at bindings 1 and 2
  StorageBuffer counters;   // dropped-list and loop-budget pixels at binding 3
  GLuint vao = 0, densityTexture = 0;
  // over particles, cellStarts and cellParticles (raymarch_cells.glsl reads them as texels), on
  // texture units 1, 2 and 3
  BufferTexels particleTexels, cellStartTexels, cellParticleTexels;
  int modelKind = 0;  // 0 homogeneous, 1 radial, 2 grid
  int gridRes = 0;

  Impl(GlContext& c, const ReferenceParticle& model)
      : context(c),
        gl(makeCurrentAndLoadGlFunctions(c)),
        budget(gl, c),
        program(linkDrawProgram(gl, {"viewport_triangle.vert.glsl"},
                                {"cloudlut_phase.glsl", "particle_common.glsl", "raymarch_cells.glsl", "loop_budget.glsl",
                                 "raymarch.frag.glsl"},
                                "#define PARTICLES_ACCESS readonly\n" + particleRecordDefines() + glslDefine("MAX_CELLS_PER_AXIS", kMaxCellsPerAxis) +
                                    glslDefine("MAX_HITS", kMaxViewHits) + glslDefine("MAX_SHADOW_HITS", kMaxShadowHits),
                                "ray-march")),
        particles(gl),
        cellStarts(gl),
        cellParticles(gl),
        counters(gl),
        particleTexels(gl, GL_RGBA32F, 16),
        cellStartTexels(gl, GL_R32UI, 4),
        cellParticleTexels(gl, GL_R32UI, 4) {
    requireParticleRecordLayout(gl, program.id(), "ray-march program");
    gl.GenVertexArrays(1, &vao);
    modelKind = model.model() == DensityModel::Sphere ? 0 : model.model() == DensityModel::Radial ? 1 : 2;
    // The density texture: the model at the nodes of its grid (node-centred sampling in the
    // shader); a 2³ placeholder for the analytic models.
    gridRes = modelKind == 2 ? model.gridResolution() : 2;
    std::vector<float> grid(static_cast<std::size_t>(gridRes) * gridRes * gridRes, 0.0f);
    if (modelKind == 2) {
      const float step = 2.0f / static_cast<float>(gridRes - 1);
      for (int k = 0; k < gridRes; ++k)
        for (int j = 0; j < gridRes; ++j)
          for (int i = 0; i < gridRes; ++i)
            grid[(static_cast<std::size_t>(k) * gridRes + j) * gridRes + i] =
                model.density(glm::vec3(-1.0f + step * static_cast<float>(i), -1.0f + step * static_cast<float>(j),
                                        -1.0f + step * static_cast<float>(k)));
    }
    densityTexture = createFloatTexture3D(gl, context, "the density grid", gridRes, gridRes, gridRes, 1, grid.data());
    checkGlError(gl, "creating the ray marcher");
  }

  ~Impl() {
    try {
      context.makeCurrent();
    } catch (const GlError&) {
      // the context is gone; the members' deletions go nowhere
    }
    gl.DeleteTextures(1, &densityTexture);
    gl.DeleteVertexArrays(1, &vao);
  }

  Image render(const std::vector<scene::Particle>& list, const RayMarchSettings& s, RenderStats* stats) {
    checkImageSize(s.width, s.height);
    if (s.steps < 1 || s.steps > 4096) throw UsageError("--steps must lie in [1, 4096]");
    if (s.shadowSteps < 1 || s.shadowSteps > 256) throw UsageError("--shadow-steps must lie in [1, 256]");
    if (s.octaves < 1 || s.octaves > 16) throw UsageError("--octaves must lie in [1, 16]");
    for (float v : {s.a, s.b, s.c})
      if (!(v >= 0.0f && v <= 1.0f)) throw UsageError("--octave-abc: a, b and c must lie in [0, 1]");
    context.makeCurrent();

    if (list.size() > budget.maxBlockBytes() / sizeof(GpuParticleRecord))
      throw UsageError(std::to_string(list.size()) + " particles exceed this OpenGL's shader storage limit");

    const scene::CameraFrame camera(s.view.camera, s.width, s.height);
    const glm::vec3 eye = camera.eye(), forward = camera.forward();
    const glm::vec3 sun = glm::normalize(s.view.lighting.sunDirection);
    // The pinhole ray is affine in the pixel coordinates once scaled to unit depth.
    const auto unitDepth = [&](float px, float py) {
      const glm::vec3 d = camera.rayDirection(px, py);
      return d / glm::dot(d, forward);
    };
    const glm::vec3 r00 = unitDepth(0.0f, 0.0f);
    const glm::vec3 rdx = (unitDepth(static_cast<float>(s.width), 0.0f) - r00) / static_cast<float>(s.width);
    const glm::vec3 rdy = (unitDepth(0.0f, static_cast<float>(s.height)) - r00) / static_cast<float>(s.height);

    const Stopwatch uploadClock;
    std::vector<GpuParticleRecord> records(list.size());
    for (std::size_t k = 0; k < list.size(); ++k) records[k] = packParticle(list[k], sun);
    particles.assign(records.empty() ? nullptr : records.data(),
                     std::max<std::size_t>(records.size(), 1) * sizeof(GpuParticleRecord));
    particles.bind(0);
    // The cell lists: at most a quarter of a storage block, and 2^24 indices.
    const ParticleCellGrid grid =
        buildParticleCellGrid(records, std::min<std::size_t>(std::size_t{1} << 24, budget.maxBlockBytes() / 16));
    cellStarts.assign(grid.cellStart.data(), grid.cellStart.size() * sizeof(std::uint32_t));
    cellParticles.assign(grid.indices.empty() ? grid.cellStart.data() : grid.indices.data(),
                         std::max<std::size_t>(grid.indices.size(), 1) * sizeof(std::uint32_t));
    cellStarts.bind(1);
    cellParticles.bind(2);
    const std::uint32_t zero[2] = {0, 0};
    counters.assign(zero, sizeof zero);
    counters.bind(3);
    if (stats) stats->uploadSeconds = uploadClock.seconds();

    FloatRenderTarget target(gl, context, s.width, s.height);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);

    gl.UseProgram(program.id());
    const ProgramUniforms uniforms(gl, program.id());
    uniforms.set("uGridOrigin", grid.origin);
    uniforms.set("uGridCell", grid.cellSize);
    uniforms.set("uGridDims", grid.dims);
    uniforms.set("uProbePasses", kLoopProbePasses);
    uniforms.set("uEye", eye);
    uniforms.set("uRay00", r00);
    uniforms.set("uRayDx", rdx);
    uniforms.set("uRayDy", rdy);
    uniforms.set("uHeight", static_cast<float>(s.height));
    const scene::Lighting& light = s.view.lighting;
    uniforms.set("uSun", sun);
    uniforms.set("uSunColor", light.sunColor);
    uniforms.set("uSkyColor", light.skyColor);
    uniforms.set("uTerms", static_cast<GLint>(s.terms));
    uniforms.set("uSteps", s.steps);
    uniforms.set("uAdaptive", s.adaptive ? 1 : 0);
    uniforms.set("uShadowSteps", s.shadowSteps);
    uniforms.set("uOctaves", s.octaves);
    uniforms.set("uOctaveABC", glm::vec3(s.a, s.b, s.c));
    uniforms.set("uFirstKind", glslKind(s.first.kind));
    uniforms.set("uFirstParam", s.first.param);
    uniforms.set("uLaterKind", glslKind(s.later.kind));
    uniforms.set("uLaterParam", s.later.param);
    uniforms.set("uSigma", s.unitOpticalRadius);
    uniforms.set("uModel", modelKind);
    uniforms.set("uGridRes", static_cast<float>(gridRes));
    uniforms.set("uMinTransmittance", s.minTransmittance);
    uniforms.set("uMinOpacityForDistance", kMinOpacityForDistance);
    uniforms.set("uNoDistance", kNoDistance);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_3D, densityTexture);
    uniforms.set("uDensity", 0);
    const auto bindTexels = [&](int unit, const BufferTexels& texels, const StorageBuffer& buffer, const char* sampler) {
      if (!texels.holds(static_cast<long double>(buffer.bytes())))
        throw GlError(std::string("ray marching: ") + sampler + " needs " + std::to_string(buffer.bytes()) +
                      " bytes of texels, over GL_MAX_TEXTURE_BUFFER_SIZE's " +
                      std::to_string(static_cast<unsigned long long>(texels.maxBytes())));
      texels.bind(unit, buffer);
      uniforms.set(sampler, unit);
    };
    bindTexels(1, particleTexels, particles, "uParticleTexels");
    bindTexels(2, cellStartTexels, cellStarts, "uCellStartTexels");
    bindTexels(3, cellParticleTexels, cellParticles, "uCellParticleTexels");

    const Stopwatch drawClock;
    gl.BindVertexArray(vao);
    gl.DrawArraysInstanced(GL_TRIANGLES, 0, 3, 1);
    gl.Finish();
    checkGlError(gl, "ray marching");
    if (stats) {
      stats->renderSeconds = drawClock.seconds();
      std::uint32_t counts[2];
      counters.read(0, sizeof counts, counts);
      stats->rayMarchDroppedPixels = counts[0];
      stats->rayMarchBudgetPixels = counts[1];
    }

    const Stopwatch readClock;
    Image image = target.readBack();
    if (stats) stats->readbackSeconds = readClock.seconds();
    return image;
  }
};

RayMarchRenderer::RayMarchRenderer(GlContext& context, const ReferenceParticle& model)
    : impl_(std::make_unique<Impl>(context, model)) {}
RayMarchRenderer::~RayMarchRenderer() = default;
Image RayMarchRenderer::render(const std::vector<scene::Particle>& particles, const RayMarchSettings& settings,
                               RenderStats* stats) {
  return impl_->render(particles, settings, stats);
}

}  // namespace cloudlut::render
