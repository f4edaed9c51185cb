#include "render/ParticlePass.h"

#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "render/DiffusionVolume.h"
#include "render/HiddenFragments.h"
#include "render/ShaderSources.h"
#include "render/SunVolume.h"
#include "render/VolumeResolve.h"

namespace cloudlut::render {

namespace {

const std::vector<std::string> kVertexFiles = {"particle_common.glsl", "particle.vert.glsl"};
const std::vector<std::string> kFragmentFiles = {
    "cloudlut_geometry.glsl", "cloudlut_phase.glsl", "cloudlut_sampling.glsl", "cloudlut_shading.glsl",
    "particle_common.glsl", "particle_varyings.glsl", "particle_chord.glsl", "volume_fragments.glsl", "sun_volume.glsl", "sun_volume_chord.glsl",
    "sun_chord_map.glsl", "cascade_columns.glsl", "sun_volume_sampling.glsl", "zenith_volume_sampling.glsl",
    "diffusion_sampling.glsl",
    "cloudlut_detail_noise.glsl", "particle_detail.glsl", "hidden_fragments.glsl", "particle.frag.glsl"};
const std::vector<std::string> kCountFragmentFiles = {"particle_common.glsl", "particle_varyings.glsl",
                                                     "particle_chord.glsl", "particle_count.frag.glsl"};
constexpr GLsizei kProxyVertices = 36;  // the box's 6 faces × 2 triangles, or the polygon's fan (particle.vert.glsl)
constexpr int kSunVolumeUnit = 3;      // texture unit after the three tables (ShadingTables)
constexpr int kZenithVolumeUnit = 4;
constexpr int kDiffusionUnit = 5;       // and 6 (DiffusionVolume::bind)
constexpr int kSunChordMapUnit = 7;    // and 8 (SunVolume::bindChordMap)

// The particle program's configuration (particle.frag.glsl, particle_detail.glsl): what the
// settings and the frame's volumes ask of the shader, as #defines.
// A volume the frame did not build is not read at all: its reads would find nothing (no cloud
// above or below, no diffusion field) and cost every fragment their texture fetches all the same.
std::string configurationDefines(const RenderSettings& s, bool volume, bool sunBuilt, bool chordMap, bool zenithBuilt,
                                 bool diffusionBuilt, bool hidden) {
  return glslDefine("PARTICLE_TERMS", s.terms) + glslDefine("PARTICLE_VOLUME", volume ? 1 : 0) +
         glslDefine("PARTICLE_HIDDEN", hidden ? 1 : 0) +
         glslDefine("PARTICLE_LIGHTING", s.lighting == LightingModel::Cloud ? 1 : 0) +
         glslDefine("PARTICLE_SUNLIGHT_VOLUME", sunBuilt && s.occlusion && s.sunlight == SunlightModel::Volume ? 1 : 0) +
         glslDefine("PARTICLE_ZENITH_VOLUME", zenithBuilt ? 1 : 0) +
         glslDefine("PARTICLE_DIFFUSION", diffusionBuilt ? 1 : 0) +
         glslDefine("PARTICLE_DETAIL_NOISE", s.detail.enabled() ? 1 : 0) + SunVolume::samplingDefines(chordMap);
}

// The proxies' raster state: back faces only (one fragment per covered pixel, the eye inside a
// box too), no depth test; colour attachment 0 blended ONE/dstColour for rgb and srcAlpha/dstAlpha
// for a, the distance attachment 1 with MIN.
void setProxyState(const GlFunctions& gl, GLenum dstColour, GLenum srcAlpha, GLenum dstAlpha) {
  gl.Disable(GL_DEPTH_TEST);
  gl.DepthMask(GL_TRUE);  // so that the next frame's depth clear writes
  gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  gl.Enable(GL_CULL_FACE);
  gl.FrontFace(GL_CCW);
  gl.CullFace(GL_FRONT);
  gl.Enable(GL_BLEND);
  gl.BlendEquationi(0, GL_FUNC_ADD);
  gl.BlendFuncSeparatei(0, GL_ONE, dstColour, srcAlpha, dstAlpha);
  gl.BlendEquationi(1, GL_MIN);
}

}  // namespace

ParticlePass::ParticlePass(const GlFunctions& gl, const GlContext& context, const io::LutSet& luts,
                           ParticleBuffers& buffers)
    : gl_(gl), buffers_(buffers), tables_(gl, context, luts), hidden_(gl) {
  // the default configuration's program now, so that a GL that cannot build it fails here
  programFor(configurationDefines(RenderSettings{}, true, true, true, false, true, true));
  gl_.GenVertexArrays(1, &vao_);
}

ParticlePass::~ParticlePass() { gl_.DeleteVertexArrays(1, &vao_); }

const GlProgram& ParticlePass::programFor(const std::string& defines) {
  const auto found = programs_.find(defines);
  if (found != programs_.end()) return found->second;
  GlProgram program =
      linkDrawProgram(gl_, kVertexFiles, kFragmentFiles,
                      VolumeResolve::fragmentDefines() + HiddenFragments::defines() + defines, "particle");
  requireParticleRecordLayout(gl_, program.id(), "particle program");
  return programs_.emplace(defines, std::move(program)).first->second;
}

void ParticlePass::bindProxies(const ProgramUniforms& uniforms, bool useOrder, float farPlane, int width, int height,
                               const RenderSettings& s) {
  const scene::CameraFrame frame(s.view.camera, width, height);
  const float nearPlane = farPlane * 1e-6f;
  uniforms.set("uViewProjection", frame.projectionMatrix(nearPlane, farPlane) * frame.viewMatrix());
  uniforms.set("uEye", frame.eye());
  uniforms.set("uNearPlane", nearPlane);
  uniforms.set("uOutlinePolygons", s.outlinePolygons ? 1 : 0);
  uniforms.set("uUseOrder", useOrder ? 1 : 0);
  buffers_.records.bind(ParticleBuffers::kRecordsBinding);
  if (buffers_.sortKeys.bytes() == 0) buffers_.sortKeys.ensure(64);
  buffers_.sortKeys.bind(ParticleBuffers::kSortKeysBinding);
  gl_.BindVertexArray(vao_);
}

void ParticlePass::countFragments(std::size_t count, bool useOrder, float farPlane, int width, int height,
                                  const RenderSettings& s) {
  if (!countProgram_.id()) {
    countProgram_ = linkDrawProgram(gl_, kVertexFiles, kCountFragmentFiles, "", "particle count");
    requireParticleRecordLayout(gl_, countProgram_.id(), "particle count program");
  }
  setProxyState(gl_, GL_ONE, GL_ONE, GL_ONE);  // counts add
  gl_.UseProgram(countProgram_.id());
  const ProgramUniforms uniforms(gl_, countProgram_.id());
  uniforms.set("uNoDistance", kNoDistance);
  bindProxies(uniforms, useOrder, farPlane, width, height, s);
  if (count > 0) gl_.DrawArraysInstanced(GL_TRIANGLES, 0, kProxyVertices, static_cast<GLsizei>(count));
  gl_.Finish();
  checkGlError(gl_, "counting the particles' fragments");
}

void ParticlePass::draw(std::size_t count, bool useOrder, bool volume, float farPlane, int width, int height,
                        const RenderSettings& s, const SunVolume& sun, bool sunBuilt, const SunVolume& zenith,
                        bool zenithBuilt, const DiffusionVolume& diffusion) {
  setProxyState(gl_, GL_SRC_ALPHA, GL_ZERO, GL_SRC_ALPHA);  // C ← R + e^{−τ}·C, T ← e^{−τ}·T

  // the chord map when it holds every chord (or when no volume was built: it is not read then)
  const bool fromMap = s.sunChordMap && (!sunBuilt || sun.chordMapComplete());
  const bool hidden = volume && cullsHidden(s, count);
  const GlProgram& program =
      programFor(configurationDefines(s, volume, sunBuilt, fromMap, zenithBuilt, diffusion.built(), hidden));
  gl_.UseProgram(program.id());
  const ProgramUniforms uniforms(gl_, program.id());
  bindProxies(uniforms, useOrder, farPlane, width, height, s);
  const scene::Lighting& light = s.view.lighting;
  uniforms.set("uSunDirection", glm::normalize(light.sunDirection));
  uniforms.set("uSunColor", light.sunColor);
  uniforms.set("uSkyColor", light.skyColor);
  uniforms.set("uSkyBelowColor", light.skyColor * light.skyBelow);
  tables_.bind(uniforms);
  uniforms.set("uMinOpacityForDistance", kMinOpacityForDistance);
  uniforms.set("uNoDistance", kNoDistance);
  uniforms.set("uDetailNoise", s.detail.packed());
  sun.bind(uniforms, kSunVolumeUnit);
  sun.bindChordMap(uniforms, kSunChordMapUnit);
  if (!sunBuilt) uniforms.set("uSunCascades", 0);
  zenith.bind(uniforms, kZenithVolumeUnit, "uZenith");
  if (!zenithBuilt) uniforms.set("uZenithCascades", 0);
  diffusion.bind(uniforms, kDiffusionUnit);
  uniforms.set("uDiffusionShare", s.diffusionShare);
  uniforms.set("uDiffusionGain", s.diffusionGain);
  if (!hidden) {
    if (count > 0) gl_.DrawArraysInstanced(GL_TRIANGLES, 0, kProxyVertices, static_cast<GLsizei>(count));
  } else {
    // front to back in kHiddenBatches batches, the hidden distances into the depth buffer between
    // two (HiddenFragments.h); LEQUAL: a proxy at exactly the hidden depth, or at the cleared 1,
    // is drawn
    const float depthScale = 1.0f / farPlane;
    hidden_.bind();
    uniforms.set("uHiddenDepthScale", depthScale);
    uniforms.set("uInstanceCount", static_cast<int>(count));
    const std::size_t batches = static_cast<std::size_t>(kHiddenBatches);
    for (std::size_t b = 0; b < batches; ++b) {
      const std::size_t first = count * b / batches, end = count * (b + 1) / batches;
      if (b > 0) {
        hidden_.fillDepth(depthScale);  // leaves its own program and state: re-apply the pass's
        setProxyState(gl_, GL_SRC_ALPHA, GL_ZERO, GL_SRC_ALPHA);
        gl_.UseProgram(program.id());
      }
      gl_.Enable(GL_DEPTH_TEST);
      gl_.DepthFunc(GL_LEQUAL);
      gl_.DepthMask(GL_FALSE);
      uniforms.set("uFirstInstance", static_cast<int>(first));
      if (end > first) gl_.DrawArraysInstanced(GL_TRIANGLES, 0, kProxyVertices, static_cast<GLsizei>(end - first));
    }
    gl_.Disable(GL_DEPTH_TEST);
    gl_.DepthMask(GL_TRUE);
  }
  gl_.Finish();
  checkGlError(gl_, "rendering the particles");
}

}  // namespace cloudlut::render
