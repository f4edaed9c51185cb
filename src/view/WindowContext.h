#pragma once
// A window with an OpenGL 4.5 core context (GLFW), usable by the renderer as its GlContext: the
// viewer and `cloudlut render` run the same Renderer, with the same context requirements.
#include <memory>
#include <string>

#include "core/Errors.h"
#include "render/GlContext.h"

struct GLFWwindow;

namespace cloudlut::view {

// There is no display to open a window on, or the windowing system offers no OpenGL 4.5 core
// context: usage error (exit 2), the message one line saying which.
struct NoWindowError : UsageError {
  using UsageError::UsageError;
};

class WindowContext final : public render::GlContext {
 public:
  // Opens a visible, fixed-size window of width × height pixels (its framebuffer may be larger
  // on high-DPI screens) with a 4.5 core context, current on the calling thread. Throws
  // NoWindowError when no display or no such context is available.
  WindowContext(int width, int height, const std::string& title);
  ~WindowContext() override;
  WindowContext(const WindowContext&) = delete;
  WindowContext& operator=(const WindowContext&) = delete;

  render::GlProc procAddress(const char* name) const override;
  void makeCurrent() override;
  std::string description() const override { return description_; }

  GLFWwindow* window() const { return window_; }
  // Framebuffer size in pixels.
  void framebufferSize(int& width, int& height) const;
  void swapBuffers();
  bool closeRequested() const;
  void setTitle(const std::string& title);

 private:
  GLFWwindow* window_ = nullptr;
  std::string description_;
};

}  // namespace cloudlut::view
