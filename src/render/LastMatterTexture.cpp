#include "render/LastMatterTexture.h"

#include <glm/vec4.hpp>

#include "render/GlResources.h"

namespace cloudlut::render {

GLuint createOpticalDepthTexture(const GlFunctions& gl, const GlContext& context, const Table4D& opticalDepth) {
  const auto d = opticalDepth.dims();
  const long long depth = static_cast<long long>(d[2]) * d[3];
  const GLuint file = createFloatTexture3D(gl, context, opticalDepth.name(), d[0], d[1], depth,
                                           opticalDepth.channelCount(), opticalDepth.data().data());
  GLuint out = 0;
  try {
    out = createFloatTexture3D(gl, context, opticalDepth.name(), d[0], d[1], depth, 4, nullptr);
    const GlProgram program = linkComputeProgram(gl, {"cloudlut_geometry.glsl", "cloudlut_sampling.glsl",
                                                      "last_matter.comp.glsl"}, "");
    gl.UseProgram(program.id());
    const ProgramUniforms u(gl, program.id());
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_3D, file);
    u.set("uOpticalDepth", 0);
    u.set("uOpticalDepthDims", glm::vec4(d[0], d[1], d[2], d[3]));
    const auto& ax = opticalDepth.axes();
    u.set("uAxisMin", glm::vec4(ax[0].min, ax[1].min, ax[2].min, ax[3].min));
    u.set("uAxisMax", glm::vec4(ax[0].max, ax[1].max, ax[2].max, ax[3].max));
    gl.BindImageTexture(0, out, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl.DispatchCompute(static_cast<GLuint>((d[0] + 7) / 8), static_cast<GLuint>((d[1] + 7) / 8),
                       static_cast<GLuint>(depth));
    gl.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    gl.BindImageTexture(0, 0, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    checkGlError(gl, "deriving the optical-depth texture's last matter");
  } catch (...) {
    gl.DeleteTextures(1, &file);
    if (out) gl.DeleteTextures(1, &out);
    throw;
  }
  gl.DeleteTextures(1, &file);
  gl.BindTexture(GL_TEXTURE_3D, out);
  return out;
}

}  // namespace cloudlut::render
