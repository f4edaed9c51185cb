#include "render/VolumeResolve.h"

#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kPoolBinding = 2;
constexpr GLuint kHeadsUnit = 0, kColourUnit = 1;
// The pool (volume_fragments.glsl, block Fragments): count, capacity, overflow, truncated pixels.
constexpr std::size_t kCounterWords = 4;
constexpr std::size_t kNodeBytes = 4 * static_cast<std::size_t>(kFragmentNodeWords);
constexpr GLuint kListEnd = 0xffffffffu;

}  // namespace

long double volumePoolBytes(int width, int height, int fragmentsPerPixel) {
  return 4.0L * kCounterWords + static_cast<long double>(kNodeBytes) * static_cast<long double>(width) *
                                    static_cast<long double>(height) * static_cast<long double>(fragmentsPerPixel);
}

VolumeResolve::VolumeResolve(const GlFunctions& gl, const StorageBudget& budget)
    : gl_(gl), budget_(budget), pool_(gl) {
  program_ = linkComputeProgram(gl, {"volume_fragments.glsl", "volume_resolve.comp.glsl"},
                                fragmentDefines() + glslDefine("MAX_SEGMENTS", kMaxSegmentsPerPixel) +
                                    glslDefine("GROUP_SIDE", kGroupSide));
}

VolumeResolve::~VolumeResolve() {
  if (heads_) gl_.DeleteTextures(1, &heads_);
  if (unusedHeads_) gl_.DeleteTextures(1, &unusedHeads_);
}

std::string VolumeResolve::fragmentDefines() { return glslDefine("FRAGMENT_NODE_WORDS", kFragmentNodeWords); }

void VolumeResolve::prepare(int width, int height, int fragmentsPerPixel) {
  budget_.require(volumePoolBytes(width, height, fragmentsPerPixel),
                  "volume blending at " + std::to_string(width) + "x" + std::to_string(height) + " with " +
                      std::to_string(fragmentsPerPixel) + " fragments per pixel (try --downscale 2)");
  const std::size_t capacity =
      static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * static_cast<std::size_t>(fragmentsPerPixel);
  pool_.ensure(4 * kCounterWords + capacity * kNodeBytes);
  const GLuint counters[kCounterWords] = {0, static_cast<GLuint>(capacity), 0, 0};
  pool_.write(0, sizeof counters, counters);
  if (!heads_ || width != width_ || height != height_) {
    if (heads_) gl_.DeleteTextures(1, &heads_);
    gl_.GenTextures(1, &heads_);
    gl_.BindTexture(GL_TEXTURE_2D, heads_);
    gl_.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, width, height);
    width_ = width;
    height_ = height;
  }
  gl_.ClearTexImage(heads_, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &kListEnd);
  gl_.BindImageTexture(kHeadsUnit, heads_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  pool_.bind(kPoolBinding);
}

void VolumeResolve::bindUnused() {
  if (pool_.bytes() == 0) pool_.ensure(64);
  pool_.bind(kPoolBinding);
  if (!unusedHeads_) {
    gl_.GenTextures(1, &unusedHeads_);
    gl_.BindTexture(GL_TEXTURE_2D, unusedHeads_);
    gl_.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32UI, 1, 1);
  }
  gl_.BindImageTexture(kHeadsUnit, unusedHeads_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

void VolumeResolve::resolve(GLuint colourTexture) {
  fullBarrier(gl_);
  gl_.UseProgram(program_.id());
  pool_.bind(kPoolBinding);
  gl_.BindImageTexture(kHeadsUnit, heads_, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
  gl_.BindImageTexture(kColourUnit, colourTexture, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  gl_.Uniform2i(program_.uniform("uSize"), width_, height_);
  gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(width_), kGroupSide),
                      groupsFor(static_cast<std::size_t>(height_), kGroupSide), 1);
  fullBarrier(gl_);
  gl_.Finish();
  checkGlError(gl_, "resolving the volume fragment lists");
}

VolumeResolve::Counts VolumeResolve::counts() const {
  GLuint c[kCounterWords] = {0, 0, 0, 0};
  pool_.read(0, sizeof c, c);
  return {c[0], c[2], c[3]};
}

}  // namespace cloudlut::render
