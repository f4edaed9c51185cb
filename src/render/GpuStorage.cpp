#include "render/GpuStorage.h"

#include <unistd.h>

#include <algorithm>

#include "core/Errors.h"

namespace cloudlut::render {

StorageBudget::StorageBudget(const GlFunctions& gl, const GlContext& context) : context_(context.description()) {
  GLint64 maxStorage = 0;
  gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxStorage);
  maxBlock_ = static_cast<std::size_t>(std::max<GLint64>(maxStorage, 0));
  const long double pages = static_cast<long double>(sysconf(_SC_PHYS_PAGES));
  const long double pageSize = static_cast<long double>(sysconf(_SC_PAGESIZE));
  const long double machine = pages > 0 && pageSize > 0 ? 0.5L * pages * pageSize : 2.0e9L;
  limit_ = std::min(machine, static_cast<long double>(maxBlock_));
}

void StorageBudget::require(long double bytes, const std::string& what) const {
  if (bytes > limit_)
    throw UsageError(what + " needs " + std::to_string(static_cast<long long>(bytes / 1048576.0L)) +
                     " MiB of GPU buffer, more than the " + std::to_string(static_cast<long long>(limit_ / 1048576.0L)) +
                     " MiB this OpenGL (" + context_ + ") and machine allow");
}

StorageBuffer::StorageBuffer(const GlFunctions& gl) : gl_(gl) { gl_.GenBuffers(1, &id_); }

StorageBuffer::~StorageBuffer() { gl_.DeleteBuffers(1, &id_); }

void StorageBuffer::ensure(std::size_t bytes) {
  if (bytes_ >= bytes && bytes_ <= 2 * bytes + (1u << 20)) return;
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, id_);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_DYNAMIC_DRAW);
  bytes_ = bytes;
}

void StorageBuffer::assign(const void* data, std::size_t bytes) {
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, id_);
  gl_.BufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(bytes), data, GL_DYNAMIC_DRAW);
  bytes_ = bytes;
}

void StorageBuffer::read(std::size_t offset, std::size_t bytes, void* out) const {
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, id_);
  gl_.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), out);
}

void StorageBuffer::write(std::size_t offset, std::size_t bytes, const void* data) const {
  gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, id_);
  gl_.BufferSubData(GL_SHADER_STORAGE_BUFFER, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes), data);
}

BufferTexels::BufferTexels(const GlFunctions& gl, GLenum format, std::size_t texelBytes)
    : gl_(gl), format_(format), texelBytes_(texelBytes) {
  GLint maxTexels = 0;
  gl_.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &maxTexels);
  maxTexels_ = maxTexels;
  gl_.GenTextures(1, &id_);
}

BufferTexels::~BufferTexels() { gl_.DeleteTextures(1, &id_); }

void BufferTexels::bind(int unit, const StorageBuffer& buffer, std::size_t bytes) const {
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_BUFFER, id_);
  gl_.TexBufferRange(GL_TEXTURE_BUFFER, format_, buffer.id(), 0, static_cast<GLsizeiptr>(bytes));
}

}  // namespace cloudlut::render
