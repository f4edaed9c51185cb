#include "render/GlResources.h"

#include <algorithm>
#include <limits>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "core/Errors.h"
#include "render/RenderTypes.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {
namespace {

const char* stageName(GLenum type) {
  return type == GL_COMPUTE_SHADER ? "compute" : type == GL_FRAGMENT_SHADER ? "fragment" : "vertex";
}

// The info log of a shader or program (getiv/getInfoLog the matching pair), up to its first NUL.
template <typename GetIv, typename GetLog>
std::string infoLog(GLuint object, GetIv getiv, GetLog getLog) {
  GLint length = 0;
  getiv(object, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
  getLog(object, length, nullptr, log.data());
  return log.c_str();
}

}  // namespace

GLuint compileShader(const GlFunctions& gl, GLenum type, const std::string& source, const std::string& legend,
                     const std::string& program) {
  const GLuint shader = gl.CreateShader(type);
  const char* text = source.c_str();
  gl.ShaderSource(shader, 1, &text, nullptr);
  gl.CompileShader(shader);
  GLint ok = 0;
  gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(shader, gl.GetShaderiv, gl.GetShaderInfoLog);
    gl.DeleteShader(shader);
    throw GlError((program.empty() ? "" : program + " ") + stageName(type) + " shader does not compile (" + legend +
                  "):\n" + log);
  }
  return shader;
}

GLuint linkProgram(const GlFunctions& gl, std::initializer_list<GLuint> shaders, const std::string& what) {
  const GLuint program = gl.CreateProgram();
  for (GLuint s : shaders) gl.AttachShader(program, s);
  gl.LinkProgram(program);
  for (GLuint s : shaders) gl.DeleteShader(s);
  GLint ok = 0;
  gl.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = infoLog(program, gl.GetProgramiv, gl.GetProgramInfoLog);
    gl.DeleteProgram(program);
    throw GlError(what + " does not link:\n" + log);
  }
  return program;
}

void deleteTexture(const GlFunctions& gl, GLuint& t) {
  if (t) gl.DeleteTextures(1, &t);
  t = 0;
}

GLuint createFloatTexture3D(const GlFunctions& gl, const GlContext& context, const std::string& what, long long width,
                            long long height, long long depth, int channels, const float* data) {
  GLint max3d = 0;
  gl.GetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max3d);
  if (width > max3d || height > max3d || depth > max3d)
    throw UsageError(what + " is " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                     std::to_string(depth) + " as a 3D texture; this OpenGL (" + context.description() +
                     ") allows at most " + std::to_string(max3d) + " texels per side");
  static const GLenum formats[4] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  static const GLint internalFormats[4] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
  GLuint texture = 0;
  gl.GenTextures(1, &texture);
  gl.BindTexture(GL_TEXTURE_3D, texture);
  gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  gl.TexImage3D(GL_TEXTURE_3D, 0, internalFormats[channels - 1], static_cast<GLsizei>(width),
                static_cast<GLsizei>(height), static_cast<GLsizei>(depth), 0, formats[channels - 1], GL_FLOAT, data);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
    gl.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_BASE_LEVEL, 0);
  gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAX_LEVEL, 0);
  return texture;
}

GlProgram::~GlProgram() {
  if (gl_ && id_) gl_->DeleteProgram(id_);
}

GlProgram::GlProgram(GlProgram&& other) noexcept : gl_(other.gl_), id_(other.id_) { other.id_ = 0; }

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
  if (this != &other) {
    if (gl_ && id_) gl_->DeleteProgram(id_);
    gl_ = other.gl_;
    id_ = other.id_;
    other.id_ = 0;
  }
  return *this;
}

GlProgram linkComputeProgram(const GlFunctions& gl, const std::vector<std::string>& files, const std::string& defines) {
  const GLuint cs = compileShader(gl, GL_COMPUTE_SHADER, assembleShader(files, defines), shaderFileLegend(files));
  return GlProgram(gl, linkProgram(gl, {cs}, "compute program " + files.back()));
}

GlProgram linkDrawProgram(const GlFunctions& gl, const std::vector<std::string>& vertexFiles,
                          const std::vector<std::string>& fragmentFiles, const std::string& defines,
                          const std::string& what) {
  const GLuint vs = compileShader(gl, GL_VERTEX_SHADER, assembleShader(vertexFiles, defines),
                                  shaderFileLegend(vertexFiles), what);
  GLuint fs = 0;
  try {
    fs = compileShader(gl, GL_FRAGMENT_SHADER, assembleShader(fragmentFiles, defines), shaderFileLegend(fragmentFiles),
                       what);
  } catch (const GlError&) {
    gl.DeleteShader(vs);
    throw;
  }
  return GlProgram(gl, linkProgram(gl, {vs, fs}, what + " program"));
}

void ProgramUniforms::set(const char* name, const glm::mat4& m) const {
  gl_.UniformMatrix4fv(location(name), 1, GL_FALSE, glm::value_ptr(m));
}

FloatRenderTarget::FloatRenderTarget(const GlFunctions& gl, const GlContext& context, int width, int height)
    : gl_(gl), width_(width), height_(height) {
  gl.GenFramebuffers(1, &framebuffer_);
  gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl.GenTextures(1, &colourTexture_);
  gl.BindTexture(GL_TEXTURE_2D, colourTexture_);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, width, height);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, colourTexture_, 0);
  gl.GenTextures(1, &distanceTexture_);
  gl.BindTexture(GL_TEXTURE_2D, distanceTexture_);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_R32F, width, height);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, distanceTexture_, 0);
  gl.GenTextures(1, &depthTexture_);
  gl.BindTexture(GL_TEXTURE_2D, depthTexture_);
  gl.TexStorage2D(GL_TEXTURE_2D, 1, GL_DEPTH_COMPONENT32F, width, height);
  gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depthTexture_, 0);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    release();
    throw GlError("the float framebuffer (RGBA32F + R32F + 32-bit float depth) is not complete on " +
                  context.description());
  }
  bind();
}

void FloatRenderTarget::bind() const {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  gl_.DrawBuffers(2, drawBuffers);
  gl_.Viewport(0, 0, width_, height_);
}

FloatRenderTarget::~FloatRenderTarget() { release(); }

void FloatRenderTarget::release() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
  gl_.DeleteFramebuffers(1, &framebuffer_);
  gl_.DeleteTextures(1, &colourTexture_);
  gl_.DeleteTextures(1, &distanceTexture_);
  gl_.DeleteTextures(1, &depthTexture_);
}

Image FloatRenderTarget::readBack() const {
  const std::size_t w = static_cast<std::size_t>(width_), pixels = w * static_cast<std::size_t>(height_);
  Image image;
  image.width = width_;
  image.height = height_;
  image.rgba.resize(pixels * 4);
  image.distance.resize(pixels);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl_.ReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, image.rgba.data());
  gl_.ReadBuffer(GL_COLOR_ATTACHMENT1);
  gl_.ReadPixels(0, 0, width_, height_, GL_RED, GL_FLOAT, image.distance.data());
  checkGlError(gl_, "reading the image back");

  // GL's rows are bottom first: swap them in place, each pair converted while in cache
  // (transmittance → alpha, kNoDistance → +∞).
  const auto convert = [&](std::size_t row) {
    float* c = image.rgba.data() + 4 * w * row;
    float* d = image.distance.data() + w * row;
    for (std::size_t x = 0; x < w; ++x) {
      c[4 * x + 3] = 1.0f - c[4 * x + 3];
      if (d[x] >= kNoDistance) d[x] = std::numeric_limits<float>::infinity();
    }
  };
  for (std::size_t top = 0, bottom = static_cast<std::size_t>(height_) - 1; top <= bottom; ++top, --bottom) {
    if (top < bottom) {
      std::swap_ranges(image.rgba.data() + 4 * w * top, image.rgba.data() + 4 * w * (top + 1),
                       image.rgba.data() + 4 * w * bottom);
      std::swap_ranges(image.distance.data() + w * top, image.distance.data() + w * (top + 1),
                       image.distance.data() + w * bottom);
      convert(bottom);
    }
    convert(top);
    if (bottom == 0) break;
  }
  return image;
}

}  // namespace cloudlut::render
