#include "view/ViewShaders.h"

#include "view/EmbeddedViewShaders.h"

namespace cloudlut::view {
namespace {

std::string embeddedFile(const std::string& name) {
  for (const embedded::EmbeddedFile& f : embedded::kEmbeddedFiles)
    if (name == f.name) return std::string("#version 450 core\n#line 1 1\n") + f.text;
  throw render::GlError("the viewer has no embedded shader " + name);
}

}  // namespace

render::GlProgram linkViewProgram(const render::GlFunctions& gl, const std::string& name) {
  const std::string legend = "source string 1 is " + name;
  const GLuint vertex = render::compileShader(gl, GL_VERTEX_SHADER, embeddedFile(name + ".vert.glsl"), legend, name);
  const GLuint fragment =
      render::compileShader(gl, GL_FRAGMENT_SHADER, embeddedFile(name + ".frag.glsl"), legend, name);
  return render::GlProgram(gl, render::linkProgram(gl, {vertex, fragment}, name));
}

}  // namespace cloudlut::view
