#pragma once
// Shows a rendered frame in the window: the read-back Image, tone-mapped on the CPU
// (DisplayToneMap.h), uploaded into an RGBA8 texture and drawn over the whole framebuffer
// (linear magnification when the window is larger than the frame). Measured on llvmpipe the
// read-back, tone mapping and upload cost a few per cent of a frame (README, "cloudlut view"),
// so the renderer keeps its one read-back interface.
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/RenderTypes.h"
#include "view/DisplayGl.h"

namespace cloudlut::view {

class FramePresenter {
 public:
  FramePresenter(const render::GlFunctions& gl, const DisplayGl& display);
  ~FramePresenter();
  FramePresenter(const FramePresenter&) = delete;
  FramePresenter& operator=(const FramePresenter&) = delete;

  // Draws the frame into the default framebuffer of framebufferWidth × framebufferHeight pixels.
  void present(const render::Image& image, const glm::vec3& background, float exposure, int framebufferWidth,
               int framebufferHeight);

 private:
  const render::GlFunctions& gl_;
  const DisplayGl& display_;
  render::GlProgram program_;
  GLuint vertexArray_ = 0;
  GLuint texture_ = 0;
  int textureWidth_ = 0, textureHeight_ = 0;
  std::vector<std::uint8_t> pixels_;
};

}  // namespace cloudlut::view
