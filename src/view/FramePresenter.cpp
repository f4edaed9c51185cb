#include "view/FramePresenter.h"

#include "view/DisplayToneMap.h"
#include "view/ViewShaders.h"

namespace cloudlut::view {

FramePresenter::FramePresenter(const render::GlFunctions& gl, const DisplayGl& display)
    : gl_(gl), display_(display), program_(linkViewProgram(gl, "view_present")) {
  gl_.GenVertexArrays(1, &vertexArray_);
  render::checkGlError(gl_, "creating the frame presenter");
}

FramePresenter::~FramePresenter() {
  if (texture_ != 0) gl_.DeleteTextures(1, &texture_);
  gl_.DeleteVertexArrays(1, &vertexArray_);
}

void FramePresenter::present(const render::Image& image, const glm::vec3& background, float exposure,
                             int framebufferWidth, int framebufferHeight) {
  toneMapForDisplay(image, background, exposure, pixels_);
  if (texture_ == 0 || textureWidth_ != image.width || textureHeight_ != image.height) {
    if (texture_ != 0) gl_.DeleteTextures(1, &texture_);
    gl_.GenTextures(1, &texture_);
    gl_.BindTexture(GL_TEXTURE_2D, texture_);
    gl_.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA8, image.width, image.height);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    textureWidth_ = image.width;
    textureHeight_ = image.height;
  }
  gl_.ActiveTexture(GL_TEXTURE0);
  gl_.BindTexture(GL_TEXTURE_2D, texture_);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  display_.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                         pixels_.data());
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 4);

  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_.Viewport(0, 0, framebufferWidth, framebufferHeight);
  gl_.Disable(GL_BLEND);
  gl_.Disable(GL_DEPTH_TEST);
  gl_.Disable(GL_CULL_FACE);
  gl_.UseProgram(program_.id());
  gl_.Uniform1i(program_.uniform("frame"), 0);
  gl_.BindVertexArray(vertexArray_);
  display_.DrawArrays(GL_TRIANGLES, 0, 3);
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
  render::checkGlError(gl_, "presenting the frame");
}

}  // namespace cloudlut::view
