#pragma once
// Lines of text drawn over the frame (frame times, counts, camera, sun), with stb_easy_font's
// bitmap glyphs: quads in window pixels, blended over a translucent backing box.
#include <string>
#include <vector>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "view/DisplayGl.h"

namespace cloudlut::view {

class TextOverlay {
 public:
  TextOverlay(const render::GlFunctions& gl, const DisplayGl& display);
  ~TextOverlay();
  TextOverlay(const TextOverlay&) = delete;
  TextOverlay& operator=(const TextOverlay&) = delete;

  // Draws `lines` from the top-left corner of the default framebuffer (framebufferWidth ×
  // framebufferHeight pixels), `scale` framebuffer pixels per glyph pixel.
  void draw(const std::vector<std::string>& lines, int framebufferWidth, int framebufferHeight, float scale);

 private:
  const render::GlFunctions& gl_;
  const DisplayGl& display_;
  render::GlProgram program_;
  GLuint vertexArray_ = 0, buffer_ = 0;
};

}  // namespace cloudlut::view
