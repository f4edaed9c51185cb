#include "view/Viewer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "core/Errors.h"
#include "io/LutIo.h"
#include "render/GlFunctions.h"
#include "render/ImageWriters.h"
#include "render/Renderer.h"
#include "scene/CameraPath.h"
#include "view/DisplayGl.h"
#include "view/FramePresenter.h"
#include "view/TextOverlay.h"
#include "view/ViewerControls.h"
#include "view/WindowContext.h"

namespace cloudlut::view {
namespace fs = std::filesystem;

std::vector<fs::path> findLutSets(const fs::path& dir) {
  if (fs::is_regular_file(dir / "manifest.json")) return {dir};
  std::vector<fs::path> sets;
  std::error_code error;
  for (const fs::directory_entry& e : fs::directory_iterator(dir, error))
    if (e.is_directory() && fs::is_regular_file(e.path() / "manifest.json")) sets.push_back(e.path());
  if (sets.empty())
    throw FileError(dir.string(), "no LUT set here (no manifest.json in it or in its subdirectories)");
  std::sort(sets.begin(), sets.end());
  return sets;
}

fs::path nextScreenshotPath(const fs::path& dir, int& from) {
  for (;; ++from) {
    char name[32];
    std::snprintf(name, sizeof name, "cloudlut_%04d.png", from);
    if (!fs::exists(dir / name)) return dir / name;
  }
}

namespace {

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string format(const char* pattern, auto... values) {
  char line[256];
  std::snprintf(line, sizeof line, pattern, values...);
  return line;
}

// Stage times summed over the frames, for the summary line.
struct StageTotals {
  int frames = 0;
  double frame = 0, generate = 0, occlusion = 0, render = 0, upscale = 0, readback = 0, display = 0;
  void add(const render::RenderStats& s, double frameSeconds, double displaySeconds) {
    ++frames;
    frame += frameSeconds;
    generate += s.generateSeconds + s.uploadSeconds;
    occlusion += s.occlusionSeconds;
    render += s.renderSeconds;
    upscale += s.upscaleSeconds;
    readback += s.readbackSeconds;
    display += displaySeconds;
  }
};

std::vector<std::string> overlayLines(const ViewerState& s, const render::RenderStats& st, double frameSeconds,
                                      double displaySeconds, const ViewerOptions& o) {
  const glm::vec3 e = s.camera.eye, sun = s.sun.direction();
  const auto on = [](unsigned b) { return b ? "on" : "off"; };
  return {format("%.0f ms a frame (%.1f fps), %zu particles", 1e3 * frameSeconds, 1.0 / std::max(frameSeconds, 1e-6),
                 st.particles),
          format("generate %.0f, occlusion %.0f%s, particles %.0f ms", 1e3 * (st.generateSeconds + st.uploadSeconds),
                 1e3 * st.occlusionSeconds, st.lightSpaceKept ? " (lighting kept)" : st.lightSpaceSunOnly ? " (sun relit)" : "", 1e3 * st.renderSeconds),
          format("resolve %.0f, upscale %.0f, read-back %.1f, display %.1f ms", 1e3 * st.resolveSeconds,
                 1e3 * st.upscaleSeconds, 1e3 * st.readbackSeconds, 1e3 * displaySeconds),
          format("quality %s, %s blending, 1/%d resolution", scene::qualityPresetNames()[s.quality].c_str(),
                 render::toString(s.blend), s.downscale),
          format("lighting %s, sunlight %s", render::toString(s.lighting), render::toString(s.sunlight)),
          format("detail noise %s, diffusion %s", on(s.detail && o.settings.detail.enabled()),
                 on(s.diffusion && o.settings.diffusionShare > 0.0f)),
          format("occlusion %s; single %s, multiple %s, ambient %s", on(s.occlusion), on(s.terms & render::kTermSingle),
                 on(s.terms & render::kTermMultiple), on(s.terms & render::kTermAmbient)),
          format("camera (%.0f, %.0f, %.0f), yaw %.1f, pitch %.1f", e.x, e.y, e.z, s.camera.yawDeg, s.camera.pitchDeg),
          format("sun (%.2f, %.2f, %.2f), speed %.0f m/s", sun.x, sun.y, sun.z, s.speed),
          format("tables %s (%zu of %zu); H hides this", o.lutSets[s.lutSet].filename().c_str(), s.lutSet + 1,
                 o.lutSets.size())};
}

// The window's callbacks reach the state through the window's user pointer.
struct InputTarget {
  ViewerState* state;
  MotionKeys motion;
  double lastX = 0, lastY = 0;
  bool dragging = false;
};

void installCallbacks(GLFWwindow* window, InputTarget& target) {
  glfwSetWindowUserPointer(window, &target);
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int action, int mods) {
    InputTarget& t = *static_cast<InputTarget*>(glfwGetWindowUserPointer(w));
    onKey(*t.state, key, action, mods);
    t.motion.onKey(key, action, glfwGetTime());
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double, double y) {
    onScroll(*static_cast<InputTarget*>(glfwGetWindowUserPointer(w))->state, y);
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double x, double y) {
    InputTarget& t = *static_cast<InputTarget*>(glfwGetWindowUserPointer(w));
    const bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
    const bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
    if ((left || right) && t.dragging) {
      const bool shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
      onDrag(*t.state, x - t.lastX, y - t.lastY, shift || right);
    }
    t.dragging = left || right;
    t.lastX = x;
    t.lastY = y;
  });
}

}  // namespace

int runViewer(const ViewerOptions& o) {
  ViewerState state;
  state.camera = FlyCamera::fromCamera(o.settings.view.camera);
  state.sun = SunAngles::fromDirection(o.settings.view.lighting.sunDirection);
  const std::vector<std::string>& qualities = scene::qualityPresetNames();
  state.quality = static_cast<std::size_t>(
      std::find(qualities.begin(), qualities.end(), o.quality) - qualities.begin());
  if (state.quality >= qualities.size()) throw UsageError("--quality: unknown preset '" + o.quality + "'");
  state.blend = o.settings.blend;
  state.terms = o.settings.terms;
  state.occlusion = o.settings.occlusion;
  state.lighting = o.settings.lighting;
  state.sunlight = o.settings.sunlight;
  state.downscale = o.settings.downscale;
  state.detail = o.settings.detail.enabled();
  state.lutSetCount = o.lutSets.size();

  WindowContext window(o.settings.width, o.settings.height, "cloudlut view");
  const render::GlFunctions gl = render::makeCurrentAndLoadGlFunctions(window);
  const DisplayGl display = loadDisplayGl(window);
  FramePresenter presenter(gl, display);
  TextOverlay overlay(gl, display);
  std::size_t loadedSet = o.lutSets.size();
  std::unique_ptr<render::Renderer> renderer;
  InputTarget input{&state, {}};
  installCallbacks(window.window(), input);

  scene::CameraPath path;
  StageTotals totals;
  int screenshotNumber = 0;
  std::optional<std::chrono::steady_clock::time_point> firstFrame;  // the recorded times count from it
  render::RenderSettings settings = o.settings;
  while (!state.quit && !window.closeRequested()) {
    glfwPollEvents();
    const auto frameStart = std::chrono::steady_clock::now();
    advance(state, input.motion.take(glfwGetTime()));
    if (loadedSet != state.lutSet) {  // one renderer at a time, rebuilt for another table set
      renderer.reset();
      const io::LutSet luts = io::readLutSet(o.lutSets[state.lutSet]);
      renderer = std::make_unique<render::Renderer>(window, luts);
      loadedSet = state.lutSet;
    }
    settings.view.camera = state.camera.camera();
    settings.view.lighting.sunDirection = state.sun.direction();
    settings.blend = state.blend;
    settings.terms = state.terms;
    settings.occlusion = state.occlusion;
    settings.lighting = state.lighting;
    settings.sunlight = state.sunlight;
    settings.downscale = state.downscale;
    settings.detail = state.detail ? o.settings.detail : DetailNoise{};
    settings.diffusionShare = state.diffusion ? o.settings.diffusionShare : 0.0f;
    render::RenderStats stats;
    const render::Image image =
        o.particles ? renderer->render(o.scene.particles, settings, &stats)
                    : renderer->renderCloudscape(o.cloudscape.cloud, scene::qualityPreset(qualities[state.quality]),
                                                 settings, &stats);
    const auto displayStart = std::chrono::steady_clock::now();
    int fbWidth = 0, fbHeight = 0;
    window.framebufferSize(fbWidth, fbHeight);
    presenter.present(image, settings.view.lighting.skyColor, o.exposure, fbWidth, fbHeight);
    const double frameSoFar = secondsSince(frameStart);
    if (state.overlay)
      overlay.draw(overlayLines(state, stats, frameSoFar, secondsSince(displayStart), o), fbWidth, fbHeight,
                   fbWidth >= 900 ? 2.0f : 1.0f);
    gl.Finish();
    const double displaySeconds = secondsSince(displayStart);
    window.swapBuffers();
    totals.add(stats, secondsSince(frameStart), displaySeconds);
    if (!firstFrame) firstFrame = frameStart;
    path.frames.push_back({std::chrono::duration<double>(frameStart - *firstFrame).count(), settings.view.camera,
                           settings.view.lighting.sunDirection});
    for (; state.screenshots > 0; --state.screenshots) {  // the frame just shown, without the overlay
      const fs::path file = nextScreenshotPath(o.screenshotDir, screenshotNumber);
      render::writePng(image, file, settings.view.lighting.skyColor, o.exposure);
      std::printf("wrote %s\n", file.c_str());
      std::fflush(stdout);
    }
    window.setTitle(format("cloudlut view - %.1f fps", 1.0 / std::max(secondsSince(frameStart), 1e-6)));
  }
  if (o.record) {
    io::writeFileAtomically(*o.record, scene::cameraPathText(path));
    std::printf("wrote %s: %zu frames\n", o.record->c_str(), path.frames.size());
  }
  const double n = std::max(totals.frames, 1);
  std::printf("cloudlut view: %d frames at %dx%d, %.2f fps; per frame: generate %.1f, occlusion %.1f, particles "
              "%.1f, upscale %.1f, read-back %.1f, display %.1f ms (%s)\n",
              totals.frames, settings.width, settings.height, totals.frames / std::max(totals.frame, 1e-9),
              1e3 * totals.generate / n, 1e3 * totals.occlusion / n, 1e3 * totals.render / n,
              1e3 * totals.upscale / n, 1e3 * totals.readback / n, 1e3 * totals.display / n,
              window.description().c_str());
  return kExitOk;
}

}  // namespace cloudlut::view
