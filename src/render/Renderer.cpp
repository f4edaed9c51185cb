#include "render/Renderer.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstring>
#include <numeric>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "core/Errors.h"
#include "core/TableLookup.h"
#include "scene/CloudscapeGrid.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

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
  glm::vec3 scatteringAxes{0.0f};  // scattering table: log2 ρ at the ends of axis 3, θS warp
};

const Table4D& requireTable(const io::LutSet& luts, const std::string& name) {
  const auto it = luts.tables.find(name);
  if (it == luts.tables.end())
    throw FileError(luts.dir.string(), "has no '" + name + "' table (the renderer needs optical_depth, "
                                       "single_scattering and multiple_scattering)");
  return it->second.table;
}

// Edge-preserving upscale of a low-resolution particle image (seed §5.4): each output pixel
// blends the four nearest low-resolution samples with bilinear weights times a depth
// similarity to the nearest sample (distance to the first matter), so that a cloud's edge
// against the sky or against a farther cloud stays sharp. Distances are taken from the nearest
// sample.
Image upscaleBilateral(const Image& low, int width, int height) {
  Image out;
  out.width = width;
  out.height = height;
  out.rgba.assign(static_cast<std::size_t>(width) * height * 4, 0.0f);
  out.distance.assign(static_cast<std::size_t>(width) * height, std::numeric_limits<float>::infinity());
  const float sx = static_cast<float>(low.width) / static_cast<float>(width);
  const float sy = static_cast<float>(low.height) / static_cast<float>(height);
  auto similarity = [](float d, float ref) {
    const bool di = std::isinf(d), ri = std::isinf(ref);
    if (di || ri) return di == ri ? 1.0f : 1e-3f;
    const float rel = std::abs(d - ref) / (0.05f * std::max(ref, 1e-6f));
    return 1.0f / (1.0f + rel * rel);
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float fx = (static_cast<float>(x) + 0.5f) * sx - 0.5f, fy = (static_cast<float>(y) + 0.5f) * sy - 0.5f;
      const int nx = std::clamp(static_cast<int>(std::lround(fx)), 0, low.width - 1);
      const int ny = std::clamp(static_cast<int>(std::lround(fy)), 0, low.height - 1);
      const float ref = low.distanceAt(nx, ny);
      const int x0 = static_cast<int>(std::floor(fx)), y0 = static_cast<int>(std::floor(fy));
      const float ax = fx - static_cast<float>(x0), ay = fy - static_cast<float>(y0);
      float acc[4] = {0, 0, 0, 0}, wsum = 0.0f;
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const int px = std::clamp(x0 + i, 0, low.width - 1), py = std::clamp(y0 + j, 0, low.height - 1);
          const float w = (i ? ax : 1.0f - ax) * (j ? ay : 1.0f - ay) * similarity(low.distanceAt(px, py), ref) + 1e-12f;
          const float* c = low.pixel(px, py);
          for (int k = 0; k < 4; ++k) acc[k] += w * c[k];
          wsum += w;
        }
      float* o = &out.rgba[4 * (static_cast<std::size_t>(y) * width + x)];
      for (int k = 0; k < 4; ++k) o[k] = acc[k] / wsum;
      out.distance[static_cast<std::size_t>(y) * width + x] = ref;
    }
  return out;
}

}  // namespace

long double volumePoolBytes(int width, int height, int fragmentsPerPixel) {
  return 16.0L + 28.0L * static_cast<long double>(width) * static_cast<long double>(height) *
                     static_cast<long double>(fragmentsPerPixel);
}

BlendMode parseBlendMode(const std::string& text) {
  if (text == "alpha") return BlendMode::Alpha;
  if (text == "volume") return BlendMode::Volume;
  throw UsageError("--blend: expected alpha or volume, got '" + text + "'");
}

const char* toString(BlendMode mode) { return mode == BlendMode::Volume ? "volume" : "alpha"; }

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

std::vector<std::size_t> backToFrontOrder(const std::vector<scene::Particle>& particles, const glm::vec3& eye) {
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
  // Compute programs: generation stages 0-2, bitonic sort, occlusion stages 0-3, volume resolve.
  GLuint generatePrograms[3] = {0, 0, 0};
  GLuint sortProgram = 0;
  GLuint occlusionPrograms[4] = {0, 0, 0, 0};
  GLuint resolveProgram = 0;
  // Buffers: sort keys (binding 1), fragments (2), tiles (3), raw sunlight (4), generation (6).
  GLuint keysBuffer = 0, fragBuffer = 0, tilesBuffer = 0, rawSunBuffer = 0, genBuffer = 0;
  GLint64 maxStorage = 0;
  TableTexture opticalDepth, single, multiple;
  float unitOpticalRadius = 0;
  int firstPhaseKind = 2;
  float firstPhaseParam = 0.9f;
  std::string luts;

  Impl(GlContext& c, const io::LutSet& set)
      : context(c), gl(makeCurrentAndLoadGlFunctions(c)), luts(set.dir.string()) {
    const Table4D& od = requireTable(set, "optical_depth");
    const Table4D& l1 = requireTable(set, "single_scattering");
    const Table4D& lm = requireTable(set, "multiple_scattering");
    // the shader decodes single_scattering as log2 and multiple_scattering as linear mean sources
    ScatteringStorage storage1, storageM;
    try {
      storage1 = scatteringStorage(l1);
      storageM = scatteringStorage(lm);
    } catch (const std::runtime_error& e) {
      throw FileError(luts, e.what());
    }
    if (storage1 != ScatteringStorage::Log2MeanSource || storageM != ScatteringStorage::MeanSource)
      throw FileError(luts, std::string("single_scattering must store '") + kSingleScatteringChannel +
                                "' and multiple_scattering '" + kMultipleScatteringChannel + "'");
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
    for (GLuint* b : {&keysBuffer, &fragBuffer, &tilesBuffer, &rawSunBuffer, &genBuffer}) gl.GenBuffers(1, b);
    gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxStorage);
    buildComputePrograms();
    checkGlError(gl, "creating the renderer");
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
    for (GLuint b : {keysBuffer, fragBuffer, tilesBuffer, rawSunBuffer, genBuffer}) gl.DeleteBuffers(1, &b);
    for (GLuint p : generatePrograms) gl.DeleteProgram(p);
    for (GLuint p : occlusionPrograms) gl.DeleteProgram(p);
    gl.DeleteProgram(sortProgram);
    gl.DeleteProgram(resolveProgram);
    if (dummyHeads) gl.DeleteTextures(1, &dummyHeads);
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
    TableTexture t;
    t.texture = createFloatTexture3D(gl, context, table.name(), d[0], d[1], static_cast<long long>(d[2]) * d[3],
                                     channels, table.data().data());
    t.dims = glm::vec4(d[0], d[1], d[2], d[3]);
    if (scattering) {
      const Axis& a = table.axes()[3];
      t.scatteringAxes = glm::vec3(static_cast<float>(a.min), static_cast<float>(a.max),
                                   static_cast<float>(table.axes()[0].warp));
      if (!std::isfinite(t.scatteringAxes.x) || !std::isfinite(t.scatteringAxes.y)) {
        gl.DeleteTextures(1, &t.texture);
        throw FileError(luts, table.name() + ": density axis range is not finite");
      }
    }
    checkGlError(gl, ("uploading table " + table.name()).c_str());
    return t;
  }

  void buildProgram() {
    const GLuint vs = compileShader(gl, GL_VERTEX_SHADER, particleVertexSource(), shaderFileLegend(false));
    const GLuint fs = compileShader(gl, GL_FRAGMENT_SHADER, particleFragmentSource(), shaderFileLegend(true));
    program = linkProgram(gl, {vs, fs}, "particle program");
  }

  GLuint linkCompute(const std::vector<std::string>& files, const std::string& defines) {
    const GLuint cs = compileShader(gl, GL_COMPUTE_SHADER, assembleShader(files, defines), shaderFileLegend(files));
    return linkProgram(gl, {cs}, "compute program " + files.back());
  }

  void buildComputePrograms() {
    for (int stage = 0; stage < 3; ++stage)
      generatePrograms[stage] =
          linkCompute({"cloudscape_grid.glsl", "particle_common.glsl", "cloudscape_generate.comp.glsl"},
                      "#define STAGE " + std::to_string(stage) + "\n");
    sortProgram = linkCompute({"bitonic_sort.comp.glsl"}, "");
    for (int stage = 0; stage < 4; ++stage)
      occlusionPrograms[stage] = linkCompute({"particle_common.glsl", "occlusion.comp.glsl"},
                                             "#define STAGE " + std::to_string(stage) + "\n");
    resolveProgram = linkCompute({"volume_resolve.comp.glsl"}, "");
  }

  GLint uniformOf(GLuint p, const char* name) const { return gl.GetUniformLocation(p, name); }

  void bindTable(const ProgramUniforms& uniforms, int unit, const char* sampler, const char* dimsName,
                 const TableTexture& t) {
    gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
    gl.BindTexture(GL_TEXTURE_3D, t.texture);
    uniforms.set(sampler, unit);
    uniforms.set(dimsName, t.dims);
  }

  void requireStorage(long double bytes, const std::string& what) const {
    const long double pages = static_cast<long double>(sysconf(_SC_PHYS_PAGES));
    const long double pageSize = static_cast<long double>(sysconf(_SC_PAGESIZE));
    const long double budget = pages > 0 && pageSize > 0 ? 0.5L * pages * pageSize : 2.0e9L;
    const long double limit = std::min(budget, static_cast<long double>(maxStorage));
    if (bytes > limit)
      throw UsageError(what + " needs " + std::to_string(static_cast<long long>(bytes / 1048576.0L)) +
                       " MiB of GPU buffer, more than the " +
                       std::to_string(static_cast<long long>(limit / 1048576.0L)) +
                       " MiB this OpenGL (" + context.description() + ") and machine allow");
  }

  // Sizes a buffer (orphaning it) when it is smaller than `bytes`.
  void ensureBuffer(GLuint buffer, std::size_t bytes, std::size_t& current) {
    if (current >= bytes && current <= 2 * bytes + (1u << 20)) return;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_DRAW);
    current = bytes;
  }
  std::size_t particleBytes = 0, keysBytes = 0, fragBytes = 0, tilesBytes = 0, rawSunBytes = 0, genBytes = 0;

  void barrier() { gl.MemoryBarrier(GL_ALL_BARRIER_BITS); }

  // ---- explicit particles -------------------------------------------------------------------
  // Uploads the particles (in `order`) as records; returns the far plane that holds them all.
  float uploadParticles(const std::vector<scene::Particle>& particles, const std::vector<std::size_t>& order,
                        const glm::vec3& eye) {
    const auto maxParticles = static_cast<std::size_t>(maxStorage) / sizeof(GpuParticle);
    if (particles.size() > maxParticles)
      throw UsageError(std::to_string(particles.size()) + " particles exceed this OpenGL's shader storage limit of " +
                       std::to_string(maxParticles) + " particles per render");
    std::vector<GpuParticle> records(order.size());
    float farthest = 0.0f;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const scene::Particle& p = particles[order[k]];
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
      r.toWorld[0][3] = 1.0f;  // sunlight until the occlusion pass
      r.toWorld[1][3] = 1.0f;  // level-of-detail weight
      const float reach = std::sqrt(3.0f) * std::max({p.radii.x, p.radii.y, p.radii.z});
      farthest = std::max(farthest, glm::length(p.center - eye) + reach);
    }
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, particleBuffer);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER,
                  static_cast<GLsizeiptr>(std::max<std::size_t>(records.size(), 1) * sizeof(GpuParticle)),
                  records.empty() ? nullptr : records.data(), GL_DYNAMIC_DRAW);
    particleBytes = std::max<std::size_t>(records.size(), 1) * sizeof(GpuParticle);
    return std::max(farthest * 1.01f, 1e-3f);
  }

  // ---- GPU generation -----------------------------------------------------------------------
  struct Generated {
    std::size_t count = 0, cells = 0;
    float farPlane = 1.0f;
  };

  Generated generate(const scene::CloudType& cloud, const scene::QualityPreset& q, const RenderSettings& s, bool sortKeys) {
    const scene::GridParameters g = scene::gridParameters(cloud, q);
    const std::size_t capacity = static_cast<std::size_t>(q.maxParticles());
    std::size_t pow2 = 1;
    while (pow2 < capacity) pow2 <<= 1;
    const std::string what = "quality '" + q.name + "' (" + std::to_string(q.ringDim) + "^2 x " +
                             std::to_string(q.rings) + " x " + std::to_string(q.layers) + " = " +
                             std::to_string(capacity) + " particle slots)";
    requireStorage(static_cast<long double>(capacity) * sizeof(GpuParticle), what);
    requireStorage(static_cast<long double>(pow2) * 8.0L, what + " sort keys");
    requireStorage(32.0L + 16.0L * static_cast<long double>(q.cellCount()), what + " cell list");
    ensureBuffer(particleBuffer, capacity * sizeof(GpuParticle), particleBytes);
    ensureBuffer(keysBuffer, pow2 * 8, keysBytes);
    ensureBuffer(genBuffer, 32 + 16 * static_cast<std::size_t>(q.cellCount()), genBytes);

    // Reset the counters; pad the keys with distance -1 (sorts last).
    const GLuint header[8] = {0, 0, static_cast<GLuint>(capacity), 0, 0, 1, 1, 0};
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, genBuffer);
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof header, header);
    float minusOne = -1.0f;
    GLuint pad[2] = {0, 0xffffffffu};
    std::memcpy(&pad[0], &minusOne, sizeof minusOne);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, keysBuffer);
    gl.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT, pad);

    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, keysBuffer);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, genBuffer);
    const scene::Frustum fr = scene::cameraFrustum(s.view.camera, s.width, s.height);
    const glm::vec3 eye = s.view.camera.eye;
    for (int stage = 0; stage < 3; ++stage) {
      const GLuint p = generatePrograms[stage];
      gl.UseProgram(p);
      gl.Uniform4fv(uniformOf(p, "uG0"), 1, glm::value_ptr(g.g0));
      gl.Uniform4fv(uniformOf(p, "uG1"), 1, glm::value_ptr(g.g1));
      gl.Uniform4fv(uniformOf(p, "uG2"), 1, glm::value_ptr(g.g2));
      gl.Uniform4fv(uniformOf(p, "uG3"), 1, glm::value_ptr(g.g3));
      gl.Uniform3f(uniformOf(p, "uEye"), eye.x, eye.y, eye.z);
      gl.Uniform4fv(uniformOf(p, "uPlanes"), 5, glm::value_ptr(fr.planes[0]));
      if (stage == 0) {
        gl.DispatchCompute(static_cast<GLuint>((q.cellCount() + 63) / 64), 1, 1);
      } else if (stage == 1) {
        gl.DispatchCompute(1, 1, 1);
      } else {
        gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, genBuffer);
        gl.DispatchComputeIndirect(16);
        gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
      }
      barrier();
    }
    GLuint counts[4] = {0, 0, 0, 0};
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, genBuffer);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counts, counts);
    checkGlError(gl, "generating the cloudscape");
    Generated out;
    out.cells = counts[0];
    out.count = std::min<std::size_t>(counts[1], capacity);
    const glm::vec2 maxR = scene::grid::cgMaxRadii(q.rings - 1, g.g0, g.g1, g.g2);
    out.farPlane = g.g3.y + 2.0f * std::max(maxR.x, maxR.y) + 1.0f;

    if (sortKeys && out.count > 1) {
      std::size_t n = 1;
      while (n < out.count) n <<= 1;
      gl.UseProgram(sortProgram);
      gl.Uniform1ui(uniformOf(sortProgram, "uCount"), static_cast<GLuint>(n));
      const GLint uK = uniformOf(sortProgram, "uK"), uJ = uniformOf(sortProgram, "uJ");
      for (std::size_t k = 2; k <= n; k <<= 1)
        for (std::size_t j = k >> 1; j > 0; j >>= 1) {
          gl.Uniform1ui(uK, static_cast<GLuint>(k));
          gl.Uniform1ui(uJ, static_cast<GLuint>(j));
          gl.DispatchCompute(static_cast<GLuint>((n + 63) / 64), 1, 1);
          gl.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
      barrier();
    }
    return out;
  }

  // ---- occlusion (seed §5.3) ----------------------------------------------------------------
  void occlude(std::size_t count, const RenderSettings& s, RenderStats* stats) {
    if (!s.occlusion || count == 0) return;
    const std::size_t headerBytes = 32 + 4 * kLightTiles * kLightTiles;
    const std::size_t nodeCapacity =
        std::min<std::size_t>(std::max<std::size_t>(count * 16, 1u << 18),
                              (static_cast<std::size_t>(maxStorage) - headerBytes) / 8);
    ensureBuffer(tilesBuffer, headerBytes + nodeCapacity * 8, tilesBytes);
    ensureBuffer(rawSunBuffer, count * 4, rawSunBytes);
    std::vector<GLuint> header(headerBytes / 4, 0xffffffffu);
    const GLint bounds[4] = {std::numeric_limits<GLint>::max(), std::numeric_limits<GLint>::max(),
                             std::numeric_limits<GLint>::min(), std::numeric_limits<GLint>::min()};
    std::memcpy(header.data(), bounds, sizeof bounds);
    header[4] = 0;
    header[5] = static_cast<GLuint>(nodeCapacity);
    header[6] = 0;
    header[7] = 0;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, tilesBuffer);
    gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(headerBytes), header.data());
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, tilesBuffer);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, rawSunBuffer);
    const glm::vec3 sun = glm::normalize(s.view.lighting.sunDirection);
    const glm::vec3 helper = std::abs(sun.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    const glm::vec3 u = glm::normalize(glm::cross(helper, sun)), v = glm::cross(sun, u);
    for (int stage = 0; stage < 4; ++stage) {
      const GLuint p = occlusionPrograms[stage];
      gl.UseProgram(p);
      gl.Uniform1ui(uniformOf(p, "uCount"), static_cast<GLuint>(count));
      gl.Uniform3f(uniformOf(p, "uSun"), sun.x, sun.y, sun.z);
      gl.Uniform3f(uniformOf(p, "uLightU"), u.x, u.y, u.z);
      gl.Uniform3f(uniformOf(p, "uLightV"), v.x, v.y, v.z);
      gl.Uniform1f(uniformOf(p, "uSigma"), unitOpticalRadius);
      gl.Uniform1f(uniformOf(p, "uXi"), kOcclusionXi);
      gl.Uniform1i(uniformOf(p, "uSmooth"), s.smoothOcclusion ? 1 : 0);
      gl.DispatchCompute(static_cast<GLuint>((count + 63) / 64), 1, 1);
      barrier();
    }
    if (stats) {
      GLuint counters[4] = {0, 0, 0, 0};
      gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, tilesBuffer);
      gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 16, sizeof counters, counters);
      stats->tileOverflow = counters[2];
    }
    checkGlError(gl, "light-space occlusion");
  }

  // ---- drawing, blending, read-back, upscale ------------------------------------------------
  Image draw(std::size_t count, bool useOrder, float farPlane, const RenderSettings& s, RenderStats* stats) {
    const int w = (s.width + s.downscale - 1) / s.downscale, h = (s.height + s.downscale - 1) / s.downscale;
    GLint maxRenderbuffer = 0, viewport[2] = {0, 0};
    gl.GetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
    gl.GetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    if (w > std::min(maxRenderbuffer, viewport[0]) || h > std::min(maxRenderbuffer, viewport[1]))
      throw UsageError("image size " + std::to_string(s.width) + "x" + std::to_string(s.height) +
                       " exceeds this OpenGL's limit of " + std::to_string(std::min(maxRenderbuffer, viewport[0])) +
                       " pixels per side");
    const bool volume = s.blend == BlendMode::Volume;
    std::size_t fragCapacity = 0;
    if (volume) {
      const long double bytes = volumePoolBytes(w, h, s.fragmentsPerPixel);
      requireStorage(bytes, "volume blending at " + std::to_string(w) + "x" + std::to_string(h) + " with " +
                                std::to_string(s.fragmentsPerPixel) + " fragments per pixel (try --downscale 2)");
      fragCapacity = static_cast<std::size_t>(w) * h * static_cast<std::size_t>(s.fragmentsPerPixel);
      ensureBuffer(fragBuffer, 16 + fragCapacity * 28, fragBytes);
      const GLuint header[4] = {0, static_cast<GLuint>(fragCapacity), 0, 0};
      gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, fragBuffer);
      gl.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof header, header);
    }

    // Float framebuffer: radiance + transmittance (a texture, for the resolve), and distance;
    // the heads of the volume lists.
    FloatRenderTarget target(gl, context, w, h);
    const GLuint colourTex = target.colourTexture();
    GLuint headsTex = 0;
    struct DeleteHeads {
      const GlFunctions& gl;
      GLuint& texture;
      ~DeleteHeads() {
        if (texture) gl.DeleteTextures(1, &texture);
      }
    } deleteHeads{gl, headsTex};
    if (volume) {
      gl.GenTextures(1, &headsTex);
      gl.BindTexture(GL_TEXTURE_2D, headsTex);
      gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, w, h);
      const GLuint nil = 0xffffffffu;
      gl.ClearTexImage(headsTex, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &nil);
      gl.BindImageTexture(0, headsTex, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    }
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
    const ProgramUniforms uniforms(gl, program);
    scene::Camera camera = s.view.camera;
    const scene::CameraFrame frame(camera, w, h);
    const glm::vec3 eye = frame.eye();
    const float nearPlane = farPlane * 1e-6f;
    const glm::mat4 viewProjection = frame.projectionMatrix(nearPlane, farPlane) * frame.viewMatrix();
    uniforms.set("uViewProjection", viewProjection);
    const scene::Lighting& light = s.view.lighting;
    uniforms.set("uEye", eye);
    const glm::vec3 sun = glm::normalize(light.sunDirection);
    uniforms.set("uSunDirection", sun);
    uniforms.set("uSunColor", light.sunColor);
    uniforms.set("uSkyColor", light.skyColor);
    uniforms.set("uTerms", static_cast<GLint>(s.terms));
    bindTable(uniforms, 0, "uOpticalDepth", "uOpticalDepthDims", opticalDepth);
    bindTable(uniforms, 1, "uSingle", "uSingleDims", single);
    bindTable(uniforms, 2, "uMultiple", "uMultipleDims", multiple);
    uniforms.set("uSingleAxes", single.scatteringAxes);
    uniforms.set("uMultipleAxes", multiple.scatteringAxes);
    uniforms.set("uUnitOpticalRadius", unitOpticalRadius);
    uniforms.set("uFirstPhaseKind", firstPhaseKind);
    uniforms.set("uFirstPhaseParam", firstPhaseParam);
    uniforms.set("uMinOpacityForDistance", kMinOpacityForDistance);
    uniforms.set("uNoDistance", kNoDistance);
    uniforms.set("uUseOrder", useOrder ? 1 : 0);
    uniforms.set("uVolume", volume ? 1 : 0);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, particleBuffer);
    if (keysBytes == 0) ensureBuffer(keysBuffer, 64, keysBytes);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, keysBuffer);
    if (fragBytes == 0) ensureBuffer(fragBuffer, 64, fragBytes);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, fragBuffer);
    if (!volume) {
      // The fragment shader declares the head image; bind a harmless one-texel target.
      if (!dummyHeads) {
        gl.GenTextures(1, &dummyHeads);
        gl.BindTexture(GL_TEXTURE_2D, dummyHeads);
        gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, 1, 1);
      }
      gl.BindImageTexture(0, dummyHeads, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    }

    const auto t1 = Clock::now();
    gl.BindVertexArray(vao);
    if (count > 0) gl.DrawArraysInstanced(GL_TRIANGLES, 0, 36, static_cast<GLsizei>(count));
    gl.Finish();
    checkGlError(gl, "rendering the particles");
    if (volume) {
      const auto t3 = Clock::now();
      barrier();
      gl.UseProgram(resolveProgram);
      gl.BindImageTexture(0, headsTex, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
      gl.BindImageTexture(1, colourTex, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
      gl.Uniform2i(uniformOf(resolveProgram, "uSize"), w, h);
      gl.DispatchCompute(static_cast<GLuint>((w + 7) / 8), static_cast<GLuint>((h + 7) / 8), 1);
      barrier();
      gl.Finish();
      checkGlError(gl, "resolving the volume fragment lists");
      if (stats) {
        stats->resolveSeconds = secondsSince(t3);
        GLuint counters[4] = {0, 0, 0, 0};
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, fragBuffer);
        gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof counters, counters);
        stats->fragments = counters[0];
        stats->fragmentOverflow = counters[2];
        stats->truncatedPixels = counters[3];
      }
    }
    if (stats) {
      stats->renderSeconds = secondsSince(t1);
      stats->particles = count;
    }

    // Read back, flip to top-first rows, and turn transmittance into alpha.
    const auto t2 = Clock::now();
    Image image = target.readBack();
    if (stats) stats->readbackSeconds = secondsSince(t2);
    if (s.downscale > 1) {
      const auto t4 = Clock::now();
      image = upscaleBilateral(image, s.width, s.height);
      if (stats) stats->upscaleSeconds = secondsSince(t4);
    }
    return image;
  }
  GLuint dummyHeads = 0;

  void validate(const RenderSettings& s) {
    checkImageSize(s.width, s.height);
    if (s.downscale != 1 && s.downscale != 2 && s.downscale != 4)
      throw UsageError("--downscale: expected 1, 2 or 4, got " + std::to_string(s.downscale));
    if (s.fragmentsPerPixel < 1 || s.fragmentsPerPixel > 1024)
      throw UsageError("fragments per pixel: expected 1 to 1024, got " + std::to_string(s.fragmentsPerPixel));
    context.makeCurrent();
  }

  Image render(const std::vector<scene::Particle>& particles, const RenderSettings& s, RenderStats* stats) {
    validate(s);
    const glm::vec3 eye = s.view.camera.eye;
    const auto t0 = Clock::now();
    std::vector<std::size_t> order;
    if (s.blend == BlendMode::Alpha) {
      order = backToFrontOrder(particles, eye);
    } else {  // order-independent: as given
      order.resize(particles.size());
      std::iota(order.begin(), order.end(), std::size_t{0});
    }
    const float farPlane = uploadParticles(particles, order, eye);
    if (stats) stats->uploadSeconds = secondsSince(t0);
    const auto t1 = Clock::now();
    occlude(particles.size(), s, stats);
    gl.Finish();
    if (stats) stats->occlusionSeconds = secondsSince(t1);
    return draw(particles.size(), false, farPlane, s, stats);
  }

  Image renderCloudscape(const scene::CloudType& cloud, const scene::QualityPreset& q, const RenderSettings& s, RenderStats* stats) {
    validate(s);
    const auto t0 = Clock::now();
    const bool alpha = s.blend == BlendMode::Alpha;
    const Generated g = generate(cloud, q, s, alpha);
    gl.Finish();
    if (stats) {
      stats->generateSeconds = secondsSince(t0);
      stats->validCells = g.cells;
    }
    const auto t1 = Clock::now();
    occlude(g.count, s, stats);
    gl.Finish();
    if (stats) stats->occlusionSeconds = secondsSince(t1);
    return draw(g.count, alpha, g.farPlane, s, stats);
  }

  std::vector<GpuParticle> readParticles(std::size_t count) {
    std::vector<GpuParticle> records(count);
    if (count == 0) return records;
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, particleBuffer);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(count * sizeof(GpuParticle)),
                        records.data());
    checkGlError(gl, "reading the particles back");
    return records;
  }

  scene::CpuGeneration generateOnGpu(const scene::CloudType& cloud, const scene::QualityPreset& q, const RenderSettings& s) {
    validate(s);
    const Generated g = generate(cloud, q, s, false);
    scene::CpuGeneration out;
    out.validCells = g.cells;
    for (const GpuParticle& r : readParticles(g.count)) {
      scene::GridParticle gp;
      gp.particle.center = {r.centerDensity[0], r.centerDensity[1], r.centerDensity[2]};
      gp.particle.density = r.centerDensity[3];
      const glm::vec3 c0(r.toWorld[0][0], r.toWorld[0][1], r.toWorld[0][2]);
      const glm::vec3 c1(r.toWorld[1][0], r.toWorld[1][1], r.toWorld[1][2]);
      const glm::vec3 c2(r.toWorld[2][0], r.toWorld[2][1], r.toWorld[2][2]);
      gp.particle.radii = {glm::length(c0), glm::length(c1), glm::length(c2)};
      gp.particle.rotation = glm::quat_cast(glm::mat3(c0 / gp.particle.radii.x, c1 / gp.particle.radii.y,
                                                       c2 / gp.particle.radii.z));
      gp.weight = r.toWorld[1][3];
      const int id = static_cast<int>(r.toParticle[0][3]);
      gp.ring = id / 16;
      gp.layer = id % 16;
      gp.cellX = static_cast<int>(r.toParticle[1][3]);
      gp.cellZ = static_cast<int>(r.toParticle[2][3]);
      out.particles.push_back(gp);
    }
    return out;
  }

  std::vector<float> sunlight(const std::vector<scene::Particle>& particles, const RenderSettings& s) {
    validate(s);
    std::vector<std::size_t> order(particles.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    uploadParticles(particles, order, s.view.camera.eye);
    occlude(particles.size(), s, nullptr);
    std::vector<float> out;
    for (const GpuParticle& r : readParticles(particles.size())) out.push_back(r.toWorld[0][3]);
    return out;
  }
};

Renderer::Renderer(GlContext& context, const io::LutSet& luts)
    : impl_(std::make_unique<Impl>(context, luts)) {}

Renderer::~Renderer() = default;

Image Renderer::render(const std::vector<scene::Particle>& particles, const RenderSettings& settings,
                       RenderStats* stats) {
  return impl_->render(particles, settings, stats);
}

Image Renderer::renderCloudscape(const scene::CloudType& cloud, const scene::QualityPreset& quality, const RenderSettings& settings,
                                 RenderStats* stats) {
  return impl_->renderCloudscape(cloud, quality, settings, stats);
}

scene::CpuGeneration Renderer::generateOnGpu(const scene::CloudType& cloud, const scene::QualityPreset& quality,
                                      const RenderSettings& settings) {
  return impl_->generateOnGpu(cloud, quality, settings);
}

std::vector<float> Renderer::sunlight(const std::vector<scene::Particle>& particles, const RenderSettings& settings) {
  return impl_->sunlight(particles, settings);
}

}  // namespace cloudlut::render
