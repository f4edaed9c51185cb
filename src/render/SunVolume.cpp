#include "render/SunVolume.h"

#include <algorithm>
#include <climits>
#include <functional>
#include <string>

#include <glm/gtc/type_ptr.hpp>

#include "core/Errors.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kDeltasBinding = 5;
constexpr GLuint kFootprintsBinding = 9;  // sun_chord_map.glsl
constexpr GLuint kChordsBinding = 10;
constexpr std::size_t kChordHeaderBytes = 16;  // sunChordsUsed, sunChordsCapacity and two pad words
constexpr std::size_t kChordBytes = 16;        // τ, wFirst, wFar and a pad word
constexpr GLuint kTauImageUnit = 2;
constexpr std::size_t kCountersBytes = 16;  // footprintOverflow and three pad words

const std::vector<std::string> kBuildFiles = {"cloudlut_geometry.glsl", "cloudlut_sampling.glsl",
                                              "cloudlut_shading.glsl",  "particle_common.glsl",
                                              "sun_volume.glsl",        "sun_volume_chord.glsl",
                                              "sun_chord_map.glsl",     "sun_volume_build.comp.glsl"};

std::string buildDefines(int stage) {
  return glslDefine("STAGE", stage) + glslDefine("GROUP_SIZE", SunVolume::kGroupSize) +
         glslDefine("SUN_CASCADES_MAX", kSunCascadesMax) + glslDefine("SUN_FOOTPRINT_MAX", kSunFootprintMax) +
         "#define SUN_FIXED_SCALE " + std::to_string(kSunFixedScale) + "\n" + particleRecordDefines();
}

}  // namespace

std::string SunVolume::samplingDefines(bool chordMap) {
  return glslDefine("SUN_CASCADES_MAX", kSunCascadesMax) + glslDefine("SUN_CHORD_MAP", chordMap ? 1 : 0);
}

SunVolume::SunVolume(const GlFunctions& gl, const GlContext& context, const StorageBudget& budget,
                     ParticleBuffers& buffers)
    : gl_(gl),
      context_(context),
      budget_(budget),
      buffers_(buffers),
      deltas_(gl),
      footprints_(gl),
      chords_(gl),
      footprintTexels_(gl, GL_RGBA32I, 16),
      chordTexels_(gl, GL_RGBA32F, 16) {
  // never empty: a program that declares the map may be drawn before any build
  footprints_.ensure(16);
  chords_.ensure(kChordHeaderBytes);
  for (int stage = 0; stage < 3; ++stage) {
    stages_[stage] = linkComputeProgram(gl, kBuildFiles, buildDefines(stage));
    requireParticleRecordLayout(gl, stages_[stage].id(), "sun_volume_build.comp.glsl");
  }
}

SunVolume::~SunVolume() {
  if (texture_) gl_.DeleteTextures(1, &texture_);
}

std::size_t SunVolume::build(const SunVolumeGrid& grid, std::size_t count, const SplatTable& table,
                             bool countOverflow, bool keepChords) {
  grid_ = grid;
  chordOuterThird_ = table.chordOuterThird;
  mapped_ = false;
  chordsNeeded_ = 0;
  const glm::ivec3 d = grid.dims;
  const glm::ivec3 texDims(d.x, d.y, d.z * grid.cascades);
  const std::size_t columns = static_cast<std::size_t>(d.x) * d.y * grid.cascades;
  const long double bytes = kCountersBytes + static_cast<long double>(columns) * (d.z + 1) * 4.0L;
  budget_.require(bytes, "the sun optical-depth volume (" + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                             std::to_string(d.z) + ", " + std::to_string(grid.cascades) + " cascades)");
  if (texDims != textureDims_) {
    if (texture_) gl_.DeleteTextures(1, &texture_);
    texture_ = 0;
    texture_ = createFloatTexture3D(gl_, context_, "the sun optical-depth volume", texDims.x, texDims.y, texDims.z, 1,
                                    nullptr);
    // Outside the columns nothing shadows: border 0 across the columns; the slices are clamped
    // by the sampler itself (cascades are stacked along them).
    const float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    gl_.TexParameterfv(GL_TEXTURE_3D, GL_TEXTURE_BORDER_COLOR, border);
    gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_BORDER);
    gl_.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_BORDER);
    textureDims_ = texDims;
  }
  deltas_.ensure(static_cast<std::size_t>(bytes));
  const GLuint zero = 0;
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, deltas_.id());
  gl_.ClearBufferData(GL_SHADER_STORAGE_BUFFER, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);

  buffers_.records.bind(ParticleBuffers::kRecordsBinding);
  deltas_.bind(kDeltasBinding);
  gl_.BindImageTexture(kTauImageUnit, texture_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_3D, table.texture);
  const auto run = [&](int stage) {
    const GlProgram& p = stages_[stage];
    gl_.UseProgram(p.id());
    const ProgramUniforms u(gl_, p.id());
    gl_.Uniform1ui(p.uniform("uCount"), static_cast<GLuint>(count));
    u.set("uSun", grid.sun);
    u.set("uSigma", table.sigma);
    u.set("uChordOuterThird", table.chordOuterThird);
    u.set("uOpticalDepth", 0);
    u.set("uOpticalDepthDims", table.dims);
    u.set("uCascades", grid.cascades);
    u.set("uMapChords", mapped_ ? 1 : 0);
    gl_.Uniform3i(p.uniform("uDims"), d.x, d.y, d.z);
    gl_.UniformMatrix4fv(p.uniform("uToGrid"), grid.cascades, GL_FALSE, glm::value_ptr(grid.toGrid[0]));
    gl_.UniformMatrix4fv(p.uniform("uToWorld"), grid.cascades, GL_FALSE, glm::value_ptr(grid.toWorld[0]));
    const std::size_t threads = stage == 1 ? columns : count;
    if (threads > 0) gl_.DispatchCompute(groupsFor(threads, kGroupSize), 1, 1);
    fullBarrier(gl_);
  };
  if (keepChords) mapped_ = sizeChordMap(count, run);
  run(0);
  run(1);
  std::size_t overflow = 0;
  if (countOverflow) {
    GLuint skipped = 0;
    deltas_.read(0, sizeof skipped, &skipped);
    overflow = skipped;
  }
  checkGlError(gl_, "building the sun optical-depth volume");
  return overflow;
}

bool SunVolume::sizeChordMap(std::size_t count, const std::function<void(int)>& run) {
  // Where each particle's chords are: a footprint per particle and cascade (16 bytes).
  const long double footprintBytes =
      static_cast<long double>(std::max<std::size_t>(count, 1)) * kSunCascadesMax * 16.0L;
  // (both are read as buffer textures too, bindChordMap: one texel per 16 bytes)
  if (footprintBytes > budget_.limitBytes() || !footprintTexels_.holds(footprintBytes)) return false;
  footprints_.ensure(static_cast<std::size_t>(footprintBytes));
  footprints_.bind(kFootprintsBinding);
  // Count the chords (STAGE 2); the map is kept only if the budget holds them all.
  const GLuint zero[4] = {0, 0, 0, 0};
  chords_.write(0, sizeof zero, zero);
  chords_.bind(kChordsBinding);
  run(2);
  GLuint needed = 0;
  chords_.read(0, sizeof needed, &needed);
  chordsNeeded_ = needed;
  const long double bytes = kChordHeaderBytes + static_cast<long double>(needed) * kChordBytes;
  if (bytes > budget_.limitBytes() || needed > static_cast<GLuint>(INT_MAX) || !chordTexels_.holds(bytes))
    return false;
  chords_.ensure(static_cast<std::size_t>(bytes));
  const GLuint header[4] = {0, needed, 0, 0};
  chords_.write(0, sizeof header, header);
  chords_.bind(kChordsBinding);
  return true;
}

void SunVolume::bind(const ProgramUniforms& uniforms, int unit, const std::string& prefix) const {
  const auto name = [&](const char* suffix) { return prefix + suffix; };
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_3D, texture_);
  uniforms.set(name("Tau").c_str(), unit);
  uniforms.set(name("Cascades").c_str(), texture_ ? grid_.cascades : 0);
  gl_.Uniform3i(uniforms.location(name("Dims").c_str()), grid_.dims.x, grid_.dims.y, grid_.dims.z);
  gl_.UniformMatrix4fv(uniforms.location(name("ToGrid").c_str()), grid_.cascades, GL_FALSE,
                       glm::value_ptr(grid_.toGrid[0]));
  gl_.UniformMatrix4fv(uniforms.location(name("ToWorld").c_str()), grid_.cascades, GL_FALSE,
                       glm::value_ptr(grid_.toWorld[0]));
  uniforms.set(name("Columns").c_str(), grid_.sun);
  uniforms.set(name("LocalCloud").c_str(), grid_.localCloud);
  uniforms.set(name("ChordOuterThird").c_str(), chordOuterThird_);
}

void SunVolume::bindChordMap(const ProgramUniforms& uniforms, int unit) const {
  // the buffers' current extent (a build may have reallocated them; sizeChordMap kept it within
  // the texel limit)
  footprintTexels_.bind(unit, footprints_);
  uniforms.set("uSunChordFootprintTexels", unit);
  chordTexels_.bind(unit + 1, chords_);
  uniforms.set("uSunChordTexels", unit + 1);
}

std::vector<float> SunVolume::readBack() const {
  std::vector<float> out(static_cast<std::size_t>(textureDims_.x) * textureDims_.y * textureDims_.z);
  if (out.empty()) return out;
  gl_.BindTexture(GL_TEXTURE_3D, texture_);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl_.GetTexImage(GL_TEXTURE_3D, 0, GL_RED, GL_FLOAT, out.data());
  checkGlError(gl_, "reading the sun optical-depth volume back");
  return out;
}

}  // namespace cloudlut::render
