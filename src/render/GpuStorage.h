#pragma once
// Shader storage buffers for the renderer's passes: a budget (what this OpenGL and this machine
// allow one buffer to hold) and an owned buffer that is sized on demand.
#include <cstddef>
#include <string>

#include "render/GlContext.h"
#include "render/GlFunctions.h"

namespace cloudlut::render {

// Bytes one shader storage buffer may hold: GL_MAX_SHADER_STORAGE_BLOCK_SIZE, and at most half
// the machine's physical memory (the GPU of a headless llvmpipe context is this machine).
class StorageBudget {
 public:
  StorageBudget(const GlFunctions& gl, const GlContext& context);

  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE alone (bytes).
  std::size_t maxBlockBytes() const { return maxBlock_; }
  // The budget itself: the smaller of maxBlockBytes() and half the physical memory (bytes).
  long double limitBytes() const { return limit_; }
  // UsageError "<what> needs N MiB of GPU buffer, more than the M MiB this OpenGL (...) and
  // machine allow" when `bytes` exceeds the budget.
  void require(long double bytes, const std::string& what) const;

 private:
  std::size_t maxBlock_ = 0;
  long double limit_ = 0;
  std::string context_;
};

// An owned shader storage buffer (deleted with it; the context must be current then).
class StorageBuffer {
 public:
  explicit StorageBuffer(const GlFunctions& gl);
  ~StorageBuffer();
  StorageBuffer(const StorageBuffer&) = delete;
  StorageBuffer& operator=(const StorageBuffer&) = delete;

  GLuint id() const { return id_; }
  std::size_t bytes() const { return bytes_; }
  // Reallocates (contents undefined) unless the buffer holds at least `bytes` and at most about
  // twice as many (so that a much smaller frame gives memory back).
  void ensure(std::size_t bytes);
  // Replaces the contents by `bytes` bytes of `data` (exactly that size).
  void assign(const void* data, std::size_t bytes);
  void bind(GLuint binding) const { gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id_); }
  // Copies `bytes` from byte `offset` of the buffer (GPU → CPU; waits for the GPU).
  void read(std::size_t offset, std::size_t bytes, void* out) const;
  void write(std::size_t offset, std::size_t bytes, const void* data) const;

 private:
  const GlFunctions& gl_;
  GLuint id_ = 0;
  std::size_t bytes_ = 0;
};

// A buffer texture (GL_TEXTURE_BUFFER) over a StorageBuffer, for shaders that read the buffer at
// indices that differ between invocations. Such a read of a storage block is, on llvmpipe, a
// bounds-checked scalar loop over the SIMD lanes, one word per lane; a texel fetch at the same
// indices is gathered with vector inserts, several times faster (docs/BENCHMARKS.md "Storage-buffer
// reads lane by lane"). The shaders that read buffers this way point here.
class BufferTexels {
 public:
  // Texels of `format`, `texelBytes` bytes each (GL_R32UI 4, GL_RGBA32F and GL_RGBA32I 16).
  BufferTexels(const GlFunctions& gl, GLenum format, std::size_t texelBytes);
  ~BufferTexels();
  BufferTexels(const BufferTexels&) = delete;
  BufferTexels& operator=(const BufferTexels&) = delete;

  // Whether `bytes` of buffer fit in GL_MAX_TEXTURE_BUFFER_SIZE texels.
  bool holds(long double bytes) const { return bytes <= maxBytes(); }
  // GL_MAX_TEXTURE_BUFFER_SIZE texels, in bytes.
  long double maxBytes() const { return static_cast<long double>(maxTexels_) * static_cast<long double>(texelBytes_); }
  // Binds the texture to texture unit `unit` over the first `bytes` of `buffer` (its current
  // storage: call after any reallocation).
  void bind(int unit, const StorageBuffer& buffer, std::size_t bytes) const;
  void bind(int unit, const StorageBuffer& buffer) const { bind(unit, buffer, buffer.bytes()); }

 private:
  const GlFunctions& gl_;
  GLuint id_ = 0;
  GLenum format_;
  std::size_t texelBytes_;
  long long maxTexels_ = 0;
};

// Every write of the passes before it visible to every read after it.
inline void fullBarrier(const GlFunctions& gl) { gl.MemoryBarrier(GL_ALL_BARRIER_BITS); }

// Work groups of `groupSize` threads that cover `threads` threads.
inline unsigned groupsFor(std::size_t threads, unsigned groupSize) {
  return static_cast<unsigned>((threads + groupSize - 1) / groupSize);
}

}  // namespace cloudlut::render
