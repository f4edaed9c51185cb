#include "render/GlFunctions.h"

#include <cstdio>
#include <string>

namespace cloudlut::render {

GlFunctions loadGlFunctions(const GlContext& context) {
  GlFunctions gl;
#define CLOUDLUT_GL_LOAD(type, name)                                                        \
  gl.name = reinterpret_cast<type>(context.procAddress("gl" #name));                         \
  if (gl.name == nullptr)                                                                   \
    throw GlError("the OpenGL context (" + context.description() + ") has no entry point gl" #name);
  CLOUDLUT_GL_FUNCTIONS(CLOUDLUT_GL_LOAD)
#undef CLOUDLUT_GL_LOAD
  return gl;
}

GlFunctions makeCurrentAndLoadGlFunctions(GlContext& context) {
  context.makeCurrent();
  return loadGlFunctions(context);
}

void checkGlError(const GlFunctions& gl, const char* what) {
  const GLenum error = gl.GetError();
  if (error == GL_NO_ERROR) return;
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", error);
  throw GlError(std::string(what) + ": OpenGL error " + code);
}

}  // namespace cloudlut::render
