#include "view/DisplayGl.h"

#include <string>

namespace cloudlut::view {

DisplayGl loadDisplayGl(const render::GlContext& context) {
  DisplayGl gl;
#define CLOUDLUT_DISPLAY_GL_LOAD(type, name)                                                  \
  gl.name = reinterpret_cast<type>(context.procAddress("gl" #name));                          \
  if (gl.name == nullptr) throw render::GlError(std::string("OpenGL entry point gl" #name " is missing"));
  CLOUDLUT_DISPLAY_GL_FUNCTIONS(CLOUDLUT_DISPLAY_GL_LOAD)
#undef CLOUDLUT_DISPLAY_GL_LOAD
  return gl;
}

}  // namespace cloudlut::view
