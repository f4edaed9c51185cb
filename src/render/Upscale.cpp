#include "render/Upscale.h"

#include <algorithm>
#include <numeric>

#include "render/ShaderSources.h"

namespace cloudlut::render {

namespace {

constexpr GLuint kLowColourUnit = 0, kLowDistanceUnit = 1;
constexpr GLuint kColourBinding = 7, kDistanceBinding = 8;
constexpr std::size_t kColourBytes = 16, kDistanceBytes = 4;  // per output pixel

}  // namespace

Upscale::Upscale(const GlFunctions& gl, const StorageBudget& budget)
    : gl_(gl), budget_(budget), colour_(gl), distance_(gl) {
  program_ = linkComputeProgram(gl, {"upscale.comp.glsl"}, glslDefine("GROUP_SIZE", kGroupSize));
}

void Upscale::run(const FloatRenderTarget& low, int width, int height) {
  // The output's bytes are within what checkImageSize allows per pixel.
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  colour_.ensure(pixels * kColourBytes);
  distance_.ensure(pixels * kDistanceBytes);
  width_ = width;
  height_ = height;

  // One binding holds at most maxBlockBytes: the rows go in bands whose offsets keep the
  // storage buffer offset alignment.
  GLint alignment = 16;
  gl_.GetIntegerv(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT, &alignment);
  const std::size_t rowBytes = static_cast<std::size_t>(width) * kDistanceBytes;
  const std::size_t rowStep = static_cast<std::size_t>(alignment) / std::gcd(rowBytes, static_cast<std::size_t>(alignment));
  std::size_t bandRows = budget_.maxBlockBytes() / (static_cast<std::size_t>(width) * kColourBytes);
  bandRows = std::max<std::size_t>(bandRows / rowStep * rowStep, 1);

  fullBarrier(gl_);
  gl_.UseProgram(program_.id());
  gl_.BindImageTexture(kLowColourUnit, low.colourTexture(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
  gl_.BindImageTexture(kLowDistanceUnit, low.distanceTexture(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
  gl_.Uniform2i(program_.uniform("uLowSize"), low.width(), low.height());
  gl_.Uniform2i(program_.uniform("uSize"), width, height);
  gl_.Uniform1f(program_.uniform("uNoDistance"), kNoDistance);
  const GLint firstRow = program_.uniform("uFirstRow");
  for (std::size_t row = 0; row < static_cast<std::size_t>(height); row += bandRows) {
    const std::size_t rows = std::min<std::size_t>(bandRows, static_cast<std::size_t>(height) - row);
    const std::size_t first = row * static_cast<std::size_t>(width), count = rows * static_cast<std::size_t>(width);
    gl_.BindBufferRange(GL_SHADER_STORAGE_BUFFER, kColourBinding, colour_.id(),
                        static_cast<GLintptr>(first * kColourBytes), static_cast<GLsizeiptr>(count * kColourBytes));
    gl_.BindBufferRange(GL_SHADER_STORAGE_BUFFER, kDistanceBinding, distance_.id(),
                        static_cast<GLintptr>(first * kDistanceBytes), static_cast<GLsizeiptr>(count * kDistanceBytes));
    gl_.Uniform1i(firstRow, static_cast<GLint>(row));
    gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(width), kGroupSize), static_cast<GLuint>(rows), 1);
  }
  fullBarrier(gl_);
  gl_.Finish();
  checkGlError(gl_, "upscaling the particle image");
}

Image Upscale::readBack() const {
  Image image;
  image.width = width_;
  image.height = height_;
  const std::size_t pixels = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  image.rgba.resize(4 * pixels);
  image.distance.resize(pixels);
  colour_.read(0, pixels * kColourBytes, image.rgba.data());
  distance_.read(0, pixels * kDistanceBytes, image.distance.data());
  checkGlError(gl_, "reading the upscaled image back");
  return image;
}

}  // namespace cloudlut::render
