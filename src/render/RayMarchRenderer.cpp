#include "render/RayMarchRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "core/Errors.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The record of raymarch.frag.glsl (std430: four vec4).
struct GpuRmParticle {
  float centerDensity[4];
  float col[3][4];
};
static_assert(sizeof(GpuRmParticle) == 64, "GpuRmParticle must match raymarch.frag.glsl");

}  // namespace

struct RayMarchRenderer::Impl {
  GlContext& context;
  GlFunctions gl;
  GLuint program = 0, vao = 0, particleBuffer = 0, densityTexture = 0;
  int modelKind = 0;  // 0 homogeneous, 1 radial, 2 grid
  int gridRes = 0;

  Impl(GlContext& c, const ReferenceParticle& model) : context(c), gl(makeCurrentAndLoadGlFunctions(c)) {
    buildProgram();
    gl.GenVertexArrays(1, &vao);
    gl.GenBuffers(1, &particleBuffer);
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
      return;
    }
    gl.DeleteTextures(1, &densityTexture);
    gl.DeleteBuffers(1, &particleBuffer);
    gl.DeleteVertexArrays(1, &vao);
    gl.DeleteProgram(program);
  }

  void buildProgram() {
    const GLuint vs = compileShader(gl, GL_VERTEX_SHADER, assembleShader({"raymarch.vert.glsl"}),
                                    "source 1 = raymarch.vert.glsl", "ray-march");
    const GLuint fs = compileShader(gl, GL_FRAGMENT_SHADER, assembleShader({"cloudlut_phase.glsl", "raymarch.frag.glsl"}),
                                    "source 1 = cloudlut_phase.glsl, 2 = raymarch.frag.glsl", "ray-march");
    program = linkProgram(gl, {vs, fs}, "ray-march program");
  }

  Image render(const std::vector<scene::Particle>& particles, const RayMarchSettings& s, RenderStats* stats) {
    checkImageSize(s.width, s.height);
    if (s.steps < 1 || s.steps > 4096) throw UsageError("--steps must lie in [1, 4096]");
    if (s.shadowSteps < 1 || s.shadowSteps > 256) throw UsageError("--shadow-steps must lie in [1, 256]");
    if (s.octaves < 1 || s.octaves > 16) throw UsageError("--octaves must lie in [1, 16]");
    for (float v : {s.a, s.b, s.c})
      if (!(v >= 0.0f && v <= 1.0f)) throw UsageError("--octave-abc: a, b and c must lie in [0, 1]");
    context.makeCurrent();

    GLint64 maxStorage = 0;
    gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxStorage);
    if (particles.size() > static_cast<std::size_t>(maxStorage) / sizeof(GpuRmParticle))
      throw UsageError(std::to_string(particles.size()) + " particles exceed this OpenGL's shader storage limit");

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

    const auto t0 = Clock::now();
    std::vector<GpuRmParticle> records(particles.size());
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const scene::Particle& p = particles[k];
      const glm::mat3 inv = p.toParticle();
      GpuRmParticle& r = records[k];
      r.centerDensity[0] = p.center.x;
      r.centerDensity[1] = p.center.y;
      r.centerDensity[2] = p.center.z;
      r.centerDensity[3] = p.density;
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 3; ++i) r.col[c][i] = inv[c][i];
      r.col[0][3] = glm::length(inv * sun);
      r.col[1][3] = 1.0001f * std::max({p.radii.x, p.radii.y, p.radii.z});
      r.col[2][3] = 0.0f;
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, particleBuffer);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER,
                  static_cast<GLsizeiptr>(std::max<std::size_t>(records.size(), 1) * sizeof(GpuRmParticle)),
                  records.empty() ? nullptr : records.data(), GL_STREAM_DRAW);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer);
    if (stats) stats->uploadSeconds = secondsSince(t0);

    FloatRenderTarget target(gl, context, s.width, s.height);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);

    gl.UseProgram(program);
    const ProgramUniforms uniforms(gl, program);
    uniforms.set("uCount", static_cast<GLint>(records.size()));
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

    const auto t1 = Clock::now();
    gl.BindVertexArray(vao);
    gl.DrawArraysInstanced(GL_TRIANGLES, 0, 3, 1);
    gl.Finish();
    checkGlError(gl, "ray marching");
    if (stats) stats->renderSeconds = secondsSince(t1);

    const auto t2 = Clock::now();
    Image image = target.readBack();
    if (stats) stats->readbackSeconds = secondsSince(t2);
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
