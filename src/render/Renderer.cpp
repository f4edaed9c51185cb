#include "render/Renderer.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include <glm/gtc/type_ptr.hpp>

#include "core/Errors.h"
#include "core/TableLookup.h"
#include "render/GlFunctions.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

// Cleared into the distance buffer and written by fragments without one; read back as +inf.
constexpr float kNoDistance = 3.0e38f;
// Bytes per pixel the render needs at its peak: the float framebuffer (20), its read-back
// copy (20), the Image (20) and an encoder's copy (≤ 24).
constexpr long double kBytesPerPixel = 84.0L;

using Clock = std::chrono::steady_clock;
double secondsSince(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The record of particle_common.glsl (std430: seven vec4).
struct GpuParticle {
  float centerDensity[4];
  float toWorld[3][4];
  float toParticle[3][4];
};
static_assert(sizeof(GpuParticle) == 7 * 16, "GpuParticle must match particle_common.glsl");

struct TableTexture {
  GLuint texture = 0;
  glm::vec4 dims{0.0f};
  glm::vec2 densityRange{0.0f};  // axis 3 of a scattering table: log2 ρ at its ends
};

const Table4D& requireTable(const io::LutSet& luts, const std::string& name) {
  const auto it = luts.tables.find(name);
  if (it == luts.tables.end())
    throw FileError(luts.dir.string(), "has no '" + name + "' table (the renderer needs optical_depth, "
                                       "single_scattering and multiple_scattering)");
  return it->second.table;
}

}  // namespace

std::size_t Image::nonFiniteCount() const {
  return static_cast<std::size_t>(
      std::count_if(rgba.begin(), rgba.end(), [](float v) { return !std::isfinite(v); }));
}

void checkImageSize(long long width, long long height) {
  if (width < 1 || height < 1)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": width and height must be at least 1");
  if (width > kMaxImageSide || height > kMaxImageSide)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                     ": width and height must be at most " + std::to_string(kMaxImageSide));
  const long double need = kBytesPerPixel * static_cast<long double>(width) * static_cast<long double>(height);
  const long double pages = static_cast<long double>(sysconf(_SC_PHYS_PAGES));
  const long double pageSize = static_cast<long double>(sysconf(_SC_PAGESIZE));
  const long double budget = pages > 0 && pageSize > 0 ? 0.5L * pages * pageSize : 2.0e9L;
  if (need > budget)
    throw UsageError("image size " + std::to_string(width) + "x" + std::to_string(height) + " would need " +
                     std::to_string(static_cast<long long>(need / 1048576.0L)) + " MiB, more than the " +
                     std::to_string(static_cast<long long>(budget / 1048576.0L)) +
                     " MiB this machine can spare");
}

std::vector<std::size_t> backToFrontOrder(const std::vector<Particle>& particles, const glm::vec3& eye) {
  std::vector<float> distance(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) distance[i] = glm::length(particles[i].center - eye);
  std::vector<std::size_t> order(particles.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return distance[a] > distance[b]; });
  return order;
}

struct Renderer::Impl {
  GlContext& context;
  GlFunctions gl;
  GLuint program = 0;
  GLuint vao = 0;
  GLuint particleBuffer = 0;
  TableTexture opticalDepth, single, multiple;
  float unitOpticalRadius = 0;
  int firstPhaseKind = 2;
  float firstPhaseParam = 0.9f;
  std::string luts;

  Impl(GlContext& c, const io::LutSet& set) : context(c), gl(loadCurrent(c)), luts(set.dir.string()) {
    const Table4D& od = requireTable(set, "optical_depth");
    const Table4D& l1 = requireTable(set, "single_scattering");
    const Table4D& lm = requireTable(set, "multiple_scattering");
    unitOpticalRadius = cloudlut::unitOpticalRadius(od);
    if (!(unitOpticalRadius > 0.0f) || !std::isfinite(unitOpticalRadius))
      throw FileError(luts, "optical_depth: extinction_per_m · radius_m is not a positive number");
    const nlohmann::json phase = l1.parameters().value("first_phase", nlohmann::json::object());
    if (!phase.is_object()) throw FileError(luts, "single_scattering: parameter first_phase is not an object");
    try {
      firstPhaseKind = phase.value("kind", 2);
      firstPhaseParam = phase.value("param", 0.9f);
    } catch (const nlohmann::json::exception&) {
      throw FileError(luts, "single_scattering: first_phase.kind/param are not numbers");
    }
    if (firstPhaseKind < 0 || firstPhaseKind > 3 || !std::isfinite(firstPhaseParam))
      throw FileError(luts, "single_scattering: unknown first_phase kind " + std::to_string(firstPhaseKind));

    opticalDepth = upload(od, false);
    single = upload(l1, true);
    multiple = upload(lm, true);
    buildProgram();
    gl.GenVertexArrays(1, &vao);
    gl.GenBuffers(1, &particleBuffer);
    checkGlError(gl, "creating the renderer");
  }

  static GlFunctions loadCurrent(GlContext& c) {
    c.makeCurrent();
    return loadGlFunctions(c);
  }

  ~Impl() {
    try {
      context.makeCurrent();
    } catch (const GlError&) {
      return;  // the context is gone with its objects
    }
    const GLuint textures[] = {opticalDepth.texture, single.texture, multiple.texture};
    gl.DeleteTextures(3, textures);
    gl.DeleteBuffers(1, &particleBuffer);
    gl.DeleteVertexArrays(1, &vao);
    gl.DeleteProgram(program);
  }

  TableTexture upload(const Table4D& table, bool scattering) {
    const auto d = table.dims();
    const int channels = table.channelCount();
    if (channels < 1 || channels > 4)
      throw FileError(luts, table.name() + ": " + std::to_string(channels) + " channels (the renderer takes 1 to 4)");
    if (table.data().size() != table.nodeCount() * static_cast<std::size_t>(channels))
      throw FileError(luts, table.name() + ": payload size does not match its dimensions");
    for (float v : table.data())
      if (!std::isfinite(v)) throw FileError(luts, table.name() + ": holds a non-finite value");
    GLint max3d = 0;
    gl.GetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
    const long long depth = static_cast<long long>(d[2]) * d[3];
    if (d[0] > max3d || d[1] > max3d || depth > max3d)
      throw UsageError(table.name() + " is " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
                       std::to_string(depth) + " as a 3D texture; this OpenGL (" + context.description() +
                       ") allows at most " + std::to_string(max3d) + " texels per side");
    TableTexture t;
    t.dims = glm::vec4(d[0], d[1], d[2], d[3]);
    if (scattering) {
      const Axis& a = table.axes()[3];
      t.densityRange = glm::vec2(static_cast<float>(a.min), static_cast<float>(a.max));
      if (!std::isfinite(t.densityRange.x) || !std::isfinite(t.densityRange.y))
        throw FileError(luts, table.name() + ": density axis range is not finite");
    }
    static const GLenum formats[4] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    static const GLint internalFormats[4] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
    gl.GenTextures(1, &t.texture);
    gl.BindTexture(GL_TEXTURE_3D, t.texture);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl.TexImage3D(GL_TEXTURE_3D, 0, internalFormats[channels - 1], d[0], d[1], static_cast<GLsizei>(depth), 0,
                  formats[channels - 1], GL_FLOAT, table.data().data());
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_BASE_LEVEL, 0);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
    checkGlError(gl, ("uploading table " + table.name()).c_str());
    return t;
  }

  GLuint compile(GLenum type, const std::string& source, bool fragment) {
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
      throw GlError(std::string(fragment ? "fragment" : "vertex") + " shader does not compile (" +
                    shaderFileLegend(fragment) + "):\n" + log.c_str());
    }
    return shader;
  }

  void buildProgram() {
    const GLuint vs = compile(GL_VERTEX_SHADER, particleVertexSource(), false);
    const GLuint fs = compile(GL_FRAGMENT_SHADER, particleFragmentSource(), true);
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
      throw GlError("particle program does not link:\n" + std::string(log.c_str()));
    }
  }

  GLint uniform(const char* name) const { return gl.GetUniformLocation(program, name); }

  void bindTable(int unit, const char* sampler, const char* dimsName, const TableTexture& t) {
    gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    gl.BindTexture(GL_TEXTURE_3D, t.texture);
    gl.Uniform1i(uniform(sampler), unit);
    gl.Uniform4f(uniform(dimsName), t.dims.x, t.dims.y, t.dims.z, t.dims.w);
  }

  Image render(const std::vector<Particle>& particles, const RenderSettings& s, RenderStats* stats) {
    checkImageSize(s.width, s.height);
    context.makeCurrent();
    GLint maxRenderbuffer = 0, viewport[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    if (s.width > std::min(maxRenderbuffer, viewport[0]) || s.height > std::min(maxRenderbuffer, viewport[1]))
      throw UsageError("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " exceeds this OpenGL's limit of " + std::to_string(std::min(maxRenderbuffer, viewport[0])) +
                       " pixels per side");

    GLint64 maxStorage = 0;
    gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxStorage);
    const auto maxParticles = static_cast<std::size_t>(maxStorage) / sizeof(GpuParticle);
    if (particles.size() > maxParticles)
      throw UsageError(std::to_string(particles.size()) + " particles exceed this OpenGL's shader storage limit of " +
                       std::to_string(maxParticles) + " particles per render");

    const CameraFrame camera(s.view.camera, s.width, s.height);
    const glm::vec3 eye = camera.eye();

    // Particle records, back to front, and the depth range that holds every bounding box.
    const auto t0 = Clock::now();
    const std::vector<std::size_t> order = backToFrontOrder(particles, eye);
    std::vector<GpuParticle> records(order.size());
    float farthest = 0.0f;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Particle& p = particles[order[k]];
      const glm::mat3 w = p.toWorld(), inv = p.toParticle();
      GpuParticle& r = records[k];
      r.centerDensity[0] = p.center.x;
      r.centerDensity[1] = p.center.y;
      r.centerDensity[2] = p.center.z;
      r.centerDensity[3] = p.density;
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 4; ++i) {
          r.toWorld[c][i] = i < 3 ? w[c][i] : 0.0f;
          r.toParticle[c][i] = i < 3 ? inv[c][i] : 0.0f;
        }
      const float reach = std::sqrt(3.0f) * std::max({p.radii.x, p.radii.y, p.radii.z});
      farthest = std::max(farthest, glm::length(p.center - eye) + reach);
    }
    const float farPlane = std::max(farthest * 1.01f, 1e-3f);
    const float nearPlane = farPlane * 1e-6f;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, particleBuffer);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER,
                  static_cast<GLsizeiptr>(std::max<std::size_t>(records.size(), 1) * sizeof(GpuParticle)),
                  records.empty() ? nullptr : records.data(), GL_STREAM_DRAW);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer);
    if (stats) stats->uploadSeconds = secondsSince(t0);

    // Float framebuffer: radiance + transmittance, and distance.
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
    const GLenum status = gl.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw GlError("the float framebuffer (RGBA32F + R32F) is not complete on " + context.description());
    const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl.DrawBuffers(2, drawBuffers);
    gl.Viewport(0, 0, s.width, s.height);
    const float clearColour[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    const float clearDistance[4] = {kNoDistance, 0.0f, 0.0f, 0.0f};
    gl.ClearBufferfv(GL_COLOR, 0, clearColour);
    gl.ClearBufferfv(GL_COLOR, 1, clearDistance);

    gl.Disable(GL_DEPTH_TEST);
    gl.Enable(GL_CULL_FACE);
    gl.FrontFace(GL_CCW);
    gl.CullFace(GL_FRONT);
    gl.Enable(GL_BLEND);
    gl.BlendEquationi(0, GL_FUNC_ADD);
    gl.BlendFuncSeparatei(0, GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_SRC_ALPHA);
    gl.BlendEquationi(1, GL_MIN);

    gl.UseProgram(program);
    const glm::mat4 viewProjection = camera.projectionMatrix(nearPlane, farPlane) * camera.viewMatrix();
    gl.UniformMatrix4fv(uniform("uViewProjection"), 1, GL_FALSE, glm::value_ptr(viewProjection));
    const Lighting& light = s.view.lighting;
    gl.Uniform3f(uniform("uEye"), eye.x, eye.y, eye.z);
    const glm::vec3 sun = glm::normalize(light.sunDirection);
    gl.Uniform3f(uniform("uSunDirection"), sun.x, sun.y, sun.z);
    gl.Uniform3f(uniform("uSunColor"), light.sunColor.x, light.sunColor.y, light.sunColor.z);
    gl.Uniform3f(uniform("uSkyColor"), light.skyColor.x, light.skyColor.y, light.skyColor.z);
    gl.Uniform1i(uniform("uTerms"), static_cast<GLint>(s.terms));
    bindTable(0, "uOpticalDepth", "uOpticalDepthDims", opticalDepth);
    bindTable(1, "uSingle", "uSingleDims", single);
    bindTable(2, "uMultiple", "uMultipleDims", multiple);
    gl.Uniform2f(uniform("uSingleDensityRange"), single.densityRange.x, single.densityRange.y);
    gl.Uniform2f(uniform("uMultipleDensityRange"), multiple.densityRange.x, multiple.densityRange.y);
    gl.Uniform1f(uniform("uUnitOpticalRadius"), unitOpticalRadius);
    gl.Uniform1i(uniform("uFirstPhaseKind"), firstPhaseKind);
    gl.Uniform1f(uniform("uFirstPhaseParam"), firstPhaseParam);
    gl.Uniform1f(uniform("uAmbientEdgeDarkening"), kAmbientEdgeDarkening);
    gl.Uniform1f(uniform("uMinOpacityForDistance"), kMinOpacityForDistance);
    gl.Uniform1f(uniform("uNoDistance"), kNoDistance);

    const auto t1 = Clock::now();
    gl.BindVertexArray(vao);
    if (!records.empty()) gl.DrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(records.size()));
    gl.Finish();
    checkGlError(gl, "rendering the particles");
    if (stats) stats->renderSeconds = secondsSince(t1);

    // Read back, flip to top-first rows, and turn transmittance into alpha.
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

Renderer::Renderer(GlContext& context, const io::LutSet& luts)
    : impl_(std::make_unique<Impl>(context, luts)) {}

Renderer::~Renderer() = default;

Image Renderer::render(const std::vector<Particle>& particles, const RenderSettings& settings,
                       RenderStats* stats) {
  return impl_->render(particles, settings, stats);
}

}  // namespace cloudlut::render
