#pragma once
// The OpenGL objects and uploads that the particle renderer (Renderer, its passes) and the ray
// marcher (RayMarchRenderer) all need: shaders and programs with the compiler's log in the error,
// float 3D textures within this OpenGL's limits, uniforms set by name, and the float render
// target (radiance + transmittance, distance) with its read-back as an Image.
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/GlContext.h"
#include "render/GlFunctions.h"

namespace cloudlut::render {

struct Image;

// Cleared into the distance attachment and written by fragments without a distance; read back
// as +infinity.
inline constexpr float kNoDistance = 3.0e38f;

// Compiles one stage from its complete source. GlError
// "[<program> ]<vertex|fragment|compute> shader does not compile (<legend>):\n<compiler log>",
// `legend` telling which source string is which file.
GLuint compileShader(const GlFunctions& gl, GLenum type, const std::string& source, const std::string& legend,
                     const std::string& program = "");

// Links the compiled shaders into a new program and deletes the shaders. GlError
// "<what> does not link:\n<linker log>".
GLuint linkProgram(const GlFunctions& gl, std::initializer_list<GLuint> shaders, const std::string& what);

// An owned program: deleted with the handle (the context must be current then).
class GlProgram {
 public:
  GlProgram() = default;
  GlProgram(const GlFunctions& gl, GLuint id) : gl_(&gl), id_(id) {}
  ~GlProgram();
  GlProgram(GlProgram&& other) noexcept;
  GlProgram& operator=(GlProgram&& other) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return id_; }
  GLint uniform(const char* name) const { return gl_->GetUniformLocation(id_, name); }

 private:
  const GlFunctions* gl_ = nullptr;
  GLuint id_ = 0;
};

// A compute program assembled from embedded shader files after `defines` (ShaderSources.h),
// compiled and linked; GlError with the compiler's log otherwise.
GlProgram linkComputeProgram(const GlFunctions& gl, const std::vector<std::string>& files, const std::string& defines);
// A vertex + fragment program, both stages assembled after the same `defines`; `what` names it
// in errors.
GlProgram linkDrawProgram(const GlFunctions& gl, const std::vector<std::string>& vertexFiles,
                          const std::vector<std::string>& fragmentFiles, const std::string& defines,
                          const std::string& what);

// A new 3D texture of `channels` (1 to 4) floats a texel (R32F, RG32F, RGB32F or RGBA32F), x
// fastest, then y, then z: linear filtering, clamped to the edges, one level; left bound to
// GL_TEXTURE_3D. UsageError naming `what` and the context when a side exceeds this OpenGL's
// GL_MAX_3D_TEXTURE_SIZE.
GLuint createFloatTexture3D(const GlFunctions& gl, const GlContext& context, const std::string& what, long long width,
                            long long height, long long depth, int channels, const float* data);

// Deletes texture `t` when it is one (non-zero) and sets it to 0.
void deleteTexture(const GlFunctions& gl, GLuint& t);

// The uniforms of one program, set by name (a name the program lacks is ignored, as GL does
// for location -1). The program must be in use when setting.
class ProgramUniforms {
 public:
  ProgramUniforms(const GlFunctions& gl, GLuint program) : gl_(gl), program_(program) {}
  GLint location(const char* name) const { return gl_.GetUniformLocation(program_, name); }
  void set(const char* name, GLint value) const { gl_.Uniform1i(location(name), value); }
  void set(const char* name, GLfloat value) const { gl_.Uniform1f(location(name), value); }
  void set(const char* name, const std::vector<float>& values) const {
    gl_.Uniform1fv(location(name), static_cast<GLsizei>(values.size()), values.data());
  }
  void set(const char* name, const glm::vec3& v) const { gl_.Uniform3f(location(name), v.x, v.y, v.z); }
  void set(const char* name, const glm::ivec3& v) const { gl_.Uniform3i(location(name), v.x, v.y, v.z); }
  void set(const char* name, const glm::vec4& v) const { gl_.Uniform4f(location(name), v.x, v.y, v.z, v.w); }
  void set(const char* name, const glm::mat4& m) const;

 private:
  const GlFunctions& gl_;
  GLuint program_;
};

// The framebuffer both renderers draw into, width × height: colour attachment 0 an RGBA32F
// texture (radiance, transmittance), attachment 1 an R32F texture (distance; both textures can
// be bound as images by compute passes), and a 32-bit float depth attachment (the particle
// pass's hidden distances, render/HiddenFragments.h). The constructor leaves it bound with both draw buffers
// enabled and the viewport covering it (GlError if the implementation cannot complete it); the
// destructor binds the default framebuffer and deletes it.
class FloatRenderTarget {
 public:
  FloatRenderTarget(const GlFunctions& gl, const GlContext& context, int width, int height);
  ~FloatRenderTarget();
  FloatRenderTarget(const FloatRenderTarget&) = delete;
  FloatRenderTarget& operator=(const FloatRenderTarget&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  GLuint colourTexture() const { return colourTexture_; }
  GLuint distanceTexture() const { return distanceTexture_; }

  // Makes it the draw framebuffer: both attachments drawn to, the viewport over them.
  void bind() const;

  // Both attachments read back (binding this framebuffer): rows top first, A = 1 − transmittance,
  // distances of kNoDistance or more as +infinity.
  Image readBack() const;

 private:
  void release();

  const GlFunctions& gl_;
  int width_, height_;
  GLuint framebuffer_ = 0, colourTexture_ = 0, distanceTexture_ = 0, depthTexture_ = 0;
};

}  // namespace cloudlut::render
