#pragma once
// The OpenGL entry points the renderer uses, loaded from a GlContext (no GLEW/glad, no reliance
// on the library exporting them). Types come from <GL/glcorearb.h>.
#include <GL/glcorearb.h>

#include "render/GlContext.h"

namespace cloudlut::render {

#define CLOUDLUT_GL_FUNCTIONS(X)                                  \
  X(PFNGLGETSTRINGPROC, GetString)                                \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                            \
  X(PFNGLGETINTEGER64VPROC, GetInteger64v)                        \
  X(PFNGLGETERRORPROC, GetError)                                  \
  X(PFNGLENABLEPROC, Enable)                                      \
  X(PFNGLDISABLEPROC, Disable)                                    \
  X(PFNGLCULLFACEPROC, CullFace)                                  \
  X(PFNGLFRONTFACEPROC, FrontFace)                                \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                \
  X(PFNGLCOLORMASKPROC, ColorMask)                                \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                              \
  X(PFNGLVIEWPORTPROC, Viewport)                                  \
  X(PFNGLSCISSORPROC, Scissor)                                    \
  X(PFNGLFINISHPROC, Finish)                                      \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                            \
  X(PFNGLGENTEXTURESPROC, GenTextures)                            \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                      \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                            \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                        \
  X(PFNGLTEXIMAGE3DPROC, TexImage3D)                              \
  X(PFNGLTEXBUFFERRANGEPROC, TexBufferRange)                      \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                        \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                    \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)              \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                    \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)      \
  X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                            \
  X(PFNGLREADBUFFERPROC, ReadBuffer)                              \
  X(PFNGLREADPIXELSPROC, ReadPixels)                              \
  X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv)                        \
  X(PFNGLBLENDFUNCSEPARATEIPROC, BlendFuncSeparatei)              \
  X(PFNGLBLENDEQUATIONIPROC, BlendEquationi)                      \
  X(PFNGLCREATESHADERPROC, CreateShader)                          \
  X(PFNGLDELETESHADERPROC, DeleteShader)                          \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                          \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                        \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                            \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                  \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                        \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                        \
  X(PFNGLATTACHSHADERPROC, AttachShader)                          \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                            \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                          \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                              \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)              \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                \
  X(PFNGLUNIFORM1FVPROC, Uniform1fv)                              \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                  \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                    \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)              \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                    \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                              \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                        \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                              \
  X(PFNGLBUFFERDATAPROC, BufferData)                              \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                      \
  X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                    \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)             \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                    \
  X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect)    \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                        \
  X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                  \
  X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                        \
  X(PFNGLCLEARTEXSUBIMAGEPROC, ClearTexSubImage)                  \
  X(PFNGLTEXSTORAGE2DPROC, TexStorage2D)                          \
  X(PFNGLBUFFERSUBDATAPROC, BufferSubData)                        \
  X(PFNGLGETBUFFERSUBDATAPROC, GetBufferSubData)                  \
  X(PFNGLCLEARBUFFERDATAPROC, ClearBufferData)                    \
  X(PFNGLUNIFORM1UIPROC, Uniform1ui)                              \
  X(PFNGLUNIFORM2IPROC, Uniform2i)                                \
  X(PFNGLUNIFORM4FVPROC, Uniform4fv)                              \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)           \
  X(PFNGLTEXPARAMETERFVPROC, TexParameterfv)                      \
  X(PFNGLGETTEXIMAGEPROC, GetTexImage)                            \
  X(PFNGLUNIFORM3IPROC, Uniform3i)                                \
  X(PFNGLGETPROGRAMRESOURCEINDEXPROC, GetProgramResourceIndex)    \
  X(PFNGLGETPROGRAMRESOURCEIVPROC, GetProgramResourceiv)

struct GlFunctions {
#define CLOUDLUT_GL_MEMBER(type, name) type name = nullptr;
  CLOUDLUT_GL_FUNCTIONS(CLOUDLUT_GL_MEMBER)
#undef CLOUDLUT_GL_MEMBER
};

// Loads every entry point above from the (current) context; throws GlError naming the first
// one that is missing.
GlFunctions loadGlFunctions(const GlContext& context);

// Makes the context current, then loads them from it.
GlFunctions makeCurrentAndLoadGlFunctions(GlContext& context);

// Throws GlError("<what>: GL error 0x...") if glGetError reports an error.
void checkGlError(const GlFunctions& gl, const char* what);

}  // namespace cloudlut::render
