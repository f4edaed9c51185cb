#include "view/TextOverlay.h"

#include <algorithm>
#include <cstring>

#include <glm/vec2.hpp>

#include "view/ViewShaders.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wshadow"
#endif
#include <stb/stb_easy_font.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace cloudlut::view {
namespace {

// stb_easy_font's vertex: x, y, z floats then 4 colour bytes.
struct QuadVertex {
  float x, y, z;
  unsigned char rgba[4];
};
static_assert(sizeof(QuadVertex) == 16);

// The quads (4 vertices each) as triangles (6 vertices), scaled and offset.
void appendTriangles(const std::vector<QuadVertex>& quads, int quadCount, float scale, glm::vec2 offset,
                     std::vector<QuadVertex>& out) {
  static constexpr int kCorners[6] = {0, 1, 2, 0, 2, 3};
  for (int q = 0; q < quadCount; ++q)
    for (int k : kCorners) {
      QuadVertex v = quads[static_cast<std::size_t>(4 * q + k)];
      v.x = offset.x + scale * v.x;
      v.y = offset.y + scale * v.y;
      out.push_back(v);
    }
}

// A box of one colour as two triangles.
void appendBox(float x0, float y0, float x1, float y1, const unsigned char (&rgba)[4], std::vector<QuadVertex>& out) {
  const float corners[6][2] = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y0}, {x1, y1}, {x0, y1}};
  for (const auto& c : corners) {
    QuadVertex v{c[0], c[1], 0.0f, {rgba[0], rgba[1], rgba[2], rgba[3]}};
    out.push_back(v);
  }
}

}  // namespace

TextOverlay::TextOverlay(const render::GlFunctions& gl, const DisplayGl& display)
    : gl_(gl), display_(display), program_(linkViewProgram(gl, "view_overlay")) {
  gl_.GenVertexArrays(1, &vertexArray_);
  gl_.GenBuffers(1, &buffer_);
  gl_.BindVertexArray(vertexArray_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, buffer_);
  display_.EnableVertexAttribArray(0);
  display_.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(QuadVertex), nullptr);
  display_.EnableVertexAttribArray(1);
  display_.VertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(QuadVertex),
                               reinterpret_cast<const void*>(offsetof(QuadVertex, rgba)));
  gl_.BindVertexArray(0);
  gl_.BindBuffer(GL_ARRAY_BUFFER, 0);
  render::checkGlError(gl_, "creating the text overlay");
}

TextOverlay::~TextOverlay() {
  gl_.DeleteBuffers(1, &buffer_);
  gl_.DeleteVertexArrays(1, &vertexArray_);
}

void TextOverlay::draw(const std::vector<std::string>& lines, int framebufferWidth, int framebufferHeight,
                       float scale) {
  if (lines.empty()) return;
  const float margin = 4.0f * scale, lineHeight = 10.0f * scale;
  std::vector<QuadVertex> triangles;
  float widest = 0.0f;
  for (const std::string& line : lines)
    widest = std::max(widest, scale * static_cast<float>(stb_easy_font_width(const_cast<char*>(line.c_str()))));
  const unsigned char backing[4] = {0, 0, 0, 140};
  appendBox(0.0f, 0.0f, widest + 2.0f * margin, 2.0f * margin + lineHeight * static_cast<float>(lines.size()),
            backing, triangles);
  std::vector<QuadVertex> quads;
  unsigned char white[4] = {255, 255, 255, 255};
  for (std::size_t i = 0; i < lines.size(); ++i) {
    quads.resize(4 * (lines[i].size() * 40 + 16));  // stb_easy_font: at most ~40 quads per character
    const int count = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(lines[i].c_str()), white, quads.data(),
                                          static_cast<int>(quads.size() * sizeof(QuadVertex)));
    appendTriangles(quads, count, scale, {margin, margin + lineHeight * static_cast<float>(i)}, triangles);
  }

  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_.Viewport(0, 0, framebufferWidth, framebufferHeight);
  gl_.Enable(GL_BLEND);
  display_.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  gl_.UseProgram(program_.id());
  gl_.Uniform2f(program_.uniform("viewportSize"), static_cast<float>(framebufferWidth),
                static_cast<float>(framebufferHeight));
  gl_.BindVertexArray(vertexArray_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, buffer_);
  gl_.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(QuadVertex)), triangles.data(),
                 GL_STREAM_DRAW);
  display_.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size()));
  gl_.BindBuffer(GL_ARRAY_BUFFER, 0);
  gl_.BindVertexArray(0);
  gl_.UseProgram(0);
  gl_.Disable(GL_BLEND);
  render::checkGlError(gl_, "drawing the overlay");
}

}  // namespace cloudlut::view
