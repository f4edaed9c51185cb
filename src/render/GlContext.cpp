// OSMesa implementation of GlContext. This is the only file that includes <GL/osmesa.h> (and,
// through it, the legacy <GL/gl.h>); everything else uses <GL/glcorearb.h> and GlFunctions.
#include "render/GlContext.h"

#include <GL/osmesa.h>

#include <array>
#include <cstring>

namespace cloudlut::render {
namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext() {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                           OSMESA_DEPTH_BITS, 0,
                           OSMESA_STENCIL_BITS, 0,
                           OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 4,
                           OSMESA_CONTEXT_MINOR_VERSION, 5,
                           0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (context_ == nullptr)
      throw GlError("OSMesa could not create an OpenGL 4.5 core profile context; " + whatIsOffered() +
                    ". The renderer needs OpenGL 4.5 core (Mesa's llvmpipe driver provides it; check "
                    "MESA_GL_VERSION_OVERRIDE and GALLIUM_DRIVER)");
    makeCurrent();
    const auto getString = reinterpret_cast<const unsigned char* (*)(unsigned)>(
        OSMesaGetProcAddress("glGetString"));
    const auto getIntegerv =
        reinterpret_cast<void (*)(unsigned, int*)>(OSMesaGetProcAddress("glGetIntegerv"));
    if (getString == nullptr || getIntegerv == nullptr) {
      OSMesaDestroyContext(context_);
      throw GlError("OSMesa context has no glGetString/glGetIntegerv");
    }
    int major = 0, minor = 0;
    getIntegerv(GL_MAJOR_VERSION, &major);
    getIntegerv(GL_MINOR_VERSION, &minor);
    const auto str = [&](unsigned name) {
      const unsigned char* s = getString(name);
      return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    description_ = "OSMesa: " + str(GL_VERSION) + ", " + str(GL_RENDERER);
    if (major < 4 || (major == 4 && minor < 5)) {
      OSMesaDestroyContext(context_);
      throw GlError("OSMesa created an OpenGL " + std::to_string(major) + "." +
                    std::to_string(minor) + " context (" + description_ +
                    "); the renderer needs OpenGL 4.5 core");
    }
  }
  ~OsMesaContext() override { OSMesaDestroyContext(context_); }
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

  // What OSMesa offers instead, probed with a context of the default version.
  static std::string whatIsOffered() {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_PROFILE, OSMESA_CORE_PROFILE, 0};
    OSMesaContext probe = OSMesaCreateContextAttribs(attribs, nullptr);
    if (probe == nullptr) return "it creates no OpenGL context at all";
    std::array<unsigned char, 4> pixel{};
    std::string offered = "it offers only";
    if (OSMesaMakeCurrent(probe, pixel.data(), GL_UNSIGNED_BYTE, 1, 1)) {
      const auto getString = reinterpret_cast<const unsigned char* (*)(unsigned)>(
          OSMesaGetProcAddress("glGetString"));
      const unsigned char* version = getString ? getString(GL_VERSION) : nullptr;
      const unsigned char* renderer = getString ? getString(GL_RENDERER) : nullptr;
      offered += std::string(" OpenGL ") + (version ? reinterpret_cast<const char*>(version) : "?") + " (" +
                 (renderer ? reinterpret_cast<const char*>(renderer) : "?") + ")";
    } else {
      offered += " a context it cannot make current";
    }
    OSMesaDestroyContext(probe);
    return offered;
  }

  GlProc procAddress(const char* name) const override {
    return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name));
  }

  void makeCurrent() override {
    if (!OSMesaMakeCurrent(context_, surface_.data(), GL_UNSIGNED_BYTE, 1, 1))
      throw GlError("OSMesaMakeCurrent failed");
  }

  std::string description() const override { return description_; }

 private:
  OSMesaContext context_ = nullptr;
  std::array<unsigned char, 4> surface_{};  // the 1×1 RGBA placeholder surface
  std::string description_;
};

}  // namespace

std::unique_ptr<GlContext> createOsMesaContext() { return std::make_unique<OsMesaContext>(); }

}  // namespace cloudlut::render
