#pragma once
// The few OpenGL entry points the viewer's display needs beyond the renderer's (GlFunctions):
// 2D texture uploads, vertex attributes and plain draws. Loaded from the window's context.
#include <GL/glcorearb.h>

#include "render/GlContext.h"

namespace cloudlut::view {

#define CLOUDLUT_DISPLAY_GL_FUNCTIONS(X)                          \
  X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                        \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                              \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)            \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)    \
  X(PFNGLCLEARCOLORPROC, ClearColor)                              \
  X(PFNGLCLEARPROC, Clear)

struct DisplayGl {
#define CLOUDLUT_DISPLAY_GL_MEMBER(type, name) type name = nullptr;
  CLOUDLUT_DISPLAY_GL_FUNCTIONS(CLOUDLUT_DISPLAY_GL_MEMBER)
#undef CLOUDLUT_DISPLAY_GL_MEMBER
};

// Loads them from the current context; render::GlError naming the first one missing.
DisplayGl loadDisplayGl(const render::GlContext& context);

}  // namespace cloudlut::view
