#pragma once
// An OpenGL 4.5 core context, behind an interface so that EGL or windowed contexts can be added
// next to the headless OSMesa one without touching the renderer.
#include <memory>
#include <stdexcept>
#include <string>

namespace cloudlut::render {

// The OpenGL implementation cannot give the renderer what it needs (no 4.5 core context, a
// missing entry point, a shader that does not compile, a table larger than its textures).
struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using GlProc = void (*)();

class GlContext {
 public:
  virtual ~GlContext() = default;
  // The address of an OpenGL entry point, or nullptr. The context must be current.
  virtual GlProc procAddress(const char* name) const = 0;
  // Makes the context current on the calling thread.
  virtual void makeCurrent() = 0;
  // e.g. "OSMesa: 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6, 256 bits)".
  virtual std::string description() const = 0;
};

// A headless OpenGL 4.5 core context from OSMesa (Mesa's llvmpipe on machines without a GPU).
// Rendering goes to framebuffer objects; the context's own surface is a 1×1 placeholder.
// Throws GlError saying what is missing when no 4.5 core context can be created.
std::unique_ptr<GlContext> createOsMesaContext();

// The headless context this build supports (OSMesa today).
inline std::unique_ptr<GlContext> createHeadlessContext() { return createOsMesaContext(); }

}  // namespace cloudlut::render
