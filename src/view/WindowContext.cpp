// GLFW implementation of the viewer's window and its context. GLFW is included without any GL
// header of its own (GLFW_INCLUDE_NONE); the entry points come from <GL/glcorearb.h>.
#include "view/WindowContext.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <GL/glcorearb.h>

#include <cstdlib>

namespace cloudlut::view {
namespace {

std::string lastGlfwError() {
  const char* text = nullptr;
  glfwGetError(&text);
  return text ? std::string(text) : std::string("no reason given");
}

}  // namespace

WindowContext::WindowContext(int width, int height, const std::string& title) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display == nullptr || *display == '\0') && (wayland == nullptr || *wayland == '\0'))
    throw NoWindowError("no display: DISPLAY is not set (cloudlut view needs a window; use cloudlut render for files)");
  if (glfwInit() != GLFW_TRUE)
    throw NoWindowError("cannot open the display '" + std::string(display ? display : wayland) +
                        "': " + lastGlfwError());
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
  glfwWindowHint(GLFW_DEPTH_BITS, 0);
  glfwWindowHint(GLFW_STENCIL_BITS, 0);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (window_ == nullptr) {
    const std::string reason = lastGlfwError();
    glfwTerminate();
    throw NoWindowError("the display offers no OpenGL 4.5 core context (" + reason +
                        "); the renderer needs OpenGL 4.5 core");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(0);
  const auto getString = reinterpret_cast<PFNGLGETSTRINGPROC>(glfwGetProcAddress("glGetString"));
  const unsigned char* version = getString ? getString(GL_VERSION) : nullptr;
  const unsigned char* renderer = getString ? getString(GL_RENDERER) : nullptr;
  description_ = std::string("GLFW: ") + (version ? reinterpret_cast<const char*>(version) : "?") + ", " +
                 (renderer ? reinterpret_cast<const char*>(renderer) : "?");
}

WindowContext::~WindowContext() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

render::GlProc WindowContext::procAddress(const char* name) const { return glfwGetProcAddress(name); }

void WindowContext::makeCurrent() { glfwMakeContextCurrent(window_); }

void WindowContext::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

void WindowContext::swapBuffers() { glfwSwapBuffers(window_); }

bool WindowContext::closeRequested() const { return glfwWindowShouldClose(window_) == GLFW_TRUE; }

void WindowContext::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

}  // namespace cloudlut::view
