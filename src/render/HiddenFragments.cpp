#include "render/HiddenFragments.h"

#include <cmath>

#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kFrontExitUnit = 2, kFrontTauUnit = 3;  // image units (hidden_fragments.glsl)
constexpr float kFrontTauSteps = 4096.0f;  // τ_front's fixed point: 1/4096 of an optical depth

GLuint newStateImage(const GlFunctions& gl, int width, int height) {
  GLuint texture = 0;
  gl.GenTextures(1, &texture);
  gl.BindTexture(GL_TEXTURE_2D, texture);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, width, height);
  return texture;
}

}  // namespace

HiddenFragments::HiddenFragments(const GlFunctions& gl) : gl_(gl) {}

HiddenFragments::~HiddenFragments() {
  if (frontExit_) gl_.DeleteTextures(1, &frontExit_);
  if (frontTau_) gl_.DeleteTextures(1, &frontTau_);
}

std::string HiddenFragments::defines() {
  return glslFloatDefine("HIDDEN_OPTICAL_DEPTH", -std::log(kHiddenTransmittance)) +
         glslFloatDefine("FRONT_TAU_UNIT", kFrontTauSteps);
}

void HiddenFragments::clear(int width, int height) {
  if (!frontExit_ || width != width_ || height != height_) {
    if (frontExit_) gl_.DeleteTextures(1, &frontExit_);
    if (frontTau_) gl_.DeleteTextures(1, &frontTau_);
    frontExit_ = newStateImage(gl_, width, height);
    frontTau_ = newStateImage(gl_, width, height);
    width_ = width;
    height_ = height;
  }
  const GLuint zero = 0;
  gl_.ClearTexImage(frontExit_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
  gl_.ClearTexImage(frontTau_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
}

void HiddenFragments::bind() const {
  gl_.BindImageTexture(kFrontExitUnit, frontExit_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  gl_.BindImageTexture(kFrontTauUnit, frontTau_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void HiddenFragments::fillDepth(float depthScale) {
  if (!depthProgram_.id())
    depthProgram_ = linkDrawProgram(gl_, {"viewport_triangle.vert.glsl"},
                                    {"hidden_fragments.glsl", "hidden_depth.frag.glsl"}, defines(), "hidden depth");
  gl_.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  gl_.UseProgram(depthProgram_.id());
  ProgramUniforms(gl_, depthProgram_.id()).set("uDepthScale", depthScale);
  gl_.Disable(GL_CULL_FACE);
  gl_.Disable(GL_BLEND);
  gl_.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  gl_.DepthFunc(GL_ALWAYS);
  gl_.DepthMask(GL_TRUE);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace cloudlut::render
