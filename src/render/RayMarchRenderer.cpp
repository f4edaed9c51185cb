#include "render/RayMarchRenderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include <glm/geometric.hpp>

#include "core/Errors.h"
#include "render/GlFunctions.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

constexpr float kNoDistance = 3.0e38f;
using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// The record of raymarch.frag.glsl (std430: four vec4).
struct GpuRmParticle {
  float centerDensity[4];
  float col[3][4];
};
static_assert(sizeof(GpuRmParticle) == 64, "GpuRmParticle must match raymarch.frag.glsl");

const char* const kFiles[2][2] = {{"raymarch.vert.glsl", nullptr}, {"cloudlut_phase.glsl", "raymarch.frag.glsl"}};

std::string assemble(bool fragment) {
  std::string source = "#version 450 core\n#define CLOUDLUT_FN\n";
  int number = 1;
  for (const char* f : kFiles[fragment ? 1 : 0]) {
    if (!f) continue;
    source += "#line 1 " + std::to_string(number++) + "\n" + embeddedShaderFile(f) + "\n";
  }
  return source;
}

}  // namespace

struct RayMarchRenderer::Impl {
  GlContext& context;
  GlFunctions gl;
  GLuint program = 0, vao = 0, particleBuffer = 0, densityTexture = 0;
  int modelKind = 0;  // 0 homogeneous, 1 radial, 2 grid
  int gridRes = 0;

  static GlFunctions loadCurrent(GlContext& c) {
    c.makeCurrent();
    return loadGlFunctions(c);
  }

  Impl(GlContext& c, const ReferenceParticle& model) : context(c), gl(loadCurrent(c)) {
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
    gl.GenTextures(1, &densityTexture);
    gl.BindTexture(GL_TEXTURE_3D, densityTexture);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexImage3D(GL_TEXTURE_3D, 0, GL_R32F, gridRes, gridRes, gridRes, 0, GL_RED, GL_FLOAT, grid.data());
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum w : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
      gl.TexParameteri(GL_TEXTURE_3D, w, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
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

  GLuint compile(GLenum type, bool fragment) {
    const std::string source = assemble(fragment);
    const GLuint shader = gl.CreateShader(type);
    const char* text = source.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint ok = 0;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      GLint length = 0;
      gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      gl.GetShaderInfoLog(shader, length, nullptr, log.data());
      gl.DeleteShader(shader);
      throw GlError(std::string("ray-march ") + (fragment ? "fragment" : "vertex") +
                    " shader does not compile (source 1 = " + (fragment ? "cloudlut_phase.glsl, 2 = raymarch.frag.glsl" : "raymarch.vert.glsl") +
                    "):\n" + log.c_str());
    }
    return shader;
  }

  void buildProgram() {
    const GLuint vs = compile(GL_VERTEX_SHADER, false), fs = compile(GL_FRAGMENT_SHADER, true);
    program = gl.CreateProgram();
    gl.AttachShader(program, vs);
    gl.AttachShader(program, fs);
    gl.LinkProgram(program);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    GLint ok = 0;
    gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
      GLint length = 0;
      gl.GetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
      std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
      gl.GetProgramInfoLog(program, length, nullptr, log.data());
      throw GlError("ray-march program does not link:\n" + std::string(log.c_str()));
    }
  }

  GLint uniform(const char* name) const { return gl.GetUniformLocation(program, name); }

  Image render(const std::vector<Particle>& particles, const RayMarchSettings& s, RenderStats* stats) {
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

    const CameraFrame camera(s.view.camera, s.width, s.height);
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
      const Particle& p = particles[k];
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

    GLuint fbo = 0, colour[2] = {0, 0};
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.GenRenderbuffers(2, colour);
    const GLenum storage[2] = {GL_RGBA32F, GL_R32F};
    for (int i = 0; i < 2; ++i) {
      gl.BindRenderbuffer(GL_RENDERBUFFER, colour[i]);
      gl.RenderbufferStorage(GL_RENDERBUFFER, storage[i], s.width, s.height);
      gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, static_cast<GLenum>(GL_COLOR_ATTACHMENT0 + i), GL_RENDERBUFFER,
                                 colour[i]);
    }
    struct Cleanup {
      const GlFunctions& gl;
      GLuint& fbo;
      GLuint* colour;
      ~Cleanup() {
        gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
        gl.DeleteFramebuffers(1, &fbo);
        gl.DeleteRenderbuffers(2, colour);
      }
    } cleanup{gl, fbo, colour};
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("the float framebuffer (RGBA32F + R32F) is not complete on " + context.description());
    const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl.DrawBuffers(2, drawBuffers);
    gl.Viewport(0, 0, s.width, s.height);
    gl.Disable(GL_DEPTH_TEST);
    gl.Disable(GL_CULL_FACE);
    gl.Disable(GL_BLEND);

    gl.UseProgram(program);
    gl.Uniform1i(uniform("uCount"), static_cast<GLint>(records.size()));
    gl.Uniform3f(uniform("uEye"), eye.x, eye.y, eye.z);
    gl.Uniform3f(uniform("uRay00"), r00.x, r00.y, r00.z);
    gl.Uniform3f(uniform("uRayDx"), rdx.x, rdx.y, rdx.z);
    gl.Uniform3f(uniform("uRayDy"), rdy.x, rdy.y, rdy.z);
    gl.Uniform1f(uniform("uHeight"), static_cast<float>(s.height));
    const Lighting& light = s.view.lighting;
    gl.Uniform3f(uniform("uSun"), sun.x, sun.y, sun.z);
    gl.Uniform3f(uniform("uSunColor"), light.sunColor.x, light.sunColor.y, light.sunColor.z);
    gl.Uniform3f(uniform("uSkyColor"), light.skyColor.x, light.skyColor.y, light.skyColor.z);
    gl.Uniform1i(uniform("uTerms"), static_cast<GLint>(s.terms));
    gl.Uniform1i(uniform("uSteps"), s.steps);
    gl.Uniform1i(uniform("uAdaptive"), s.adaptive ? 1 : 0);
    gl.Uniform1i(uniform("uShadowSteps"), s.shadowSteps);
    gl.Uniform1i(uniform("uOctaves"), s.octaves);
    gl.Uniform3f(uniform("uOctaveABC"), s.a, s.b, s.c);
    gl.Uniform1i(uniform("uFirstKind"), s.first.kind);
    gl.Uniform1f(uniform("uFirstParam"), s.first.param);
    gl.Uniform1i(uniform("uLaterKind"), s.later.kind);
    gl.Uniform1f(uniform("uLaterParam"), s.later.param);
    gl.Uniform1f(uniform("uSigma"), s.unitOpticalRadius);
    gl.Uniform1i(uniform("uModel"), modelKind);
    gl.Uniform1f(uniform("uGridRes"), static_cast<float>(gridRes));
    gl.Uniform1f(uniform("uMinTransmittance"), s.minTransmittance);
    gl.Uniform1f(uniform("uMinOpacityForDistance"), kMinOpacityForDistance);
    gl.Uniform1f(uniform("uNoDistance"), kNoDistance);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_3D, densityTexture);
    gl.Uniform1i(uniform("uDensity"), 0);

    const auto t1 = Clock::now();
    gl.BindVertexArray(vao);
    gl.DrawArraysInstanced(GL_TRIANGLES, 0, 3, 1);
    gl.Finish();
    checkGlError(gl, "ray marching");
    if (stats) stats->renderSeconds = secondsSince(t1);

    const auto t2 = Clock::now();
    const std::size_t pixels = static_cast<std::size_t>(s.width) * static_cast<std::size_t>(s.height);
    std::vector<float> colourData(pixels * 4), distanceData(pixels);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
    gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
    gl.ReadPixels(0, 0, s.width, s.height, GL_RGBA, GL_FLOAT, colourData.data());
    gl.ReadBuffer(GL_COLOR_ATTACHMENT1);
    gl.ReadPixels(0, 0, s.width, s.height, GL_RED, GL_FLOAT, distanceData.data());
    checkGlError(gl, "reading the image back");
    Image image;
    image.width = s.width;
    image.height = s.height;
    image.rgba.resize(pixels * 4);
    image.distance.resize(pixels);
    const std::size_t w = static_cast<std::size_t>(s.width);
    for (int y = 0; y < s.height; ++y) {
      const std::size_t src = static_cast<std::size_t>(s.height - 1 - y) * w, dst = static_cast<std::size_t>(y) * w;
      for (std::size_t x = 0; x < w; ++x) {
        const float* c = &colourData[4 * (src + x)];
        float* o = &image.rgba[4 * (dst + x)];
        o[0] = c[0];
        o[1] = c[1];
        o[2] = c[2];
        o[3] = 1.0f - c[3];
        const float d = distanceData[src + x];
        image.distance[dst + x] = d >= kNoDistance ? std::numeric_limits<float>::infinity() : d;
      }
    }
    if (stats) stats->readbackSeconds = secondsSince(t2);
    return image;
  }
};

RayMarchRenderer::RayMarchRenderer(GlContext& context, const ReferenceParticle& model)
    : impl_(std::make_unique<Impl>(context, model)) {}
RayMarchRenderer::~RayMarchRenderer() = default;
Image RayMarchRenderer::render(const std::vector<Particle>& particles, const RayMarchSettings& settings,
                               RenderStats* stats) {
  return impl_->render(particles, settings, stats);
}

}  // namespace cloudlut::render
