#include "render/Upscale.h"

#include "render/GpuStorage.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {

Upscale::Upscale(const GlFunctions& gl) : gl_(gl) {
  program_ = linkComputeProgram(gl, {"upscale.comp.glsl"}, glslDefine("GROUP_SIDE", kGroupSide));
}

void Upscale::run(const FloatRenderTarget& low, const FloatRenderTarget& full) {
  fullBarrier(gl_);
  gl_.UseProgram(program_.id());
  gl_.BindImageTexture(0, low.colourTexture(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  gl_.BindImageTexture(1, low.distanceTexture(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  gl_.BindImageTexture(2, full.colourTexture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  gl_.BindImageTexture(3, full.distanceTexture(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  gl_.Uniform2i(program_.uniform("uLowSize"), low.width(), low.height());
  gl_.Uniform2i(program_.uniform("uSize"), full.width(), full.height());
  gl_.Uniform1f(program_.uniform("uNoDistance"), kNoDistance);
  gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(full.width()), kGroupSide),
                      groupsFor(static_cast<std::size_t>(full.height()), kGroupSide), 1);
  fullBarrier(gl_);
  gl_.Finish();
  checkGlError(gl_, "upscaling the particle image");
}

}  // namespace cloudlut::render
