#pragma once
// `cloudlut view`: a window flying through a cloudscape (or a particle scene) rendered frame by
// frame by the same Renderer as `cloudlut render`, in a GLFW window's OpenGL 4.5 core context.
// Controls: ViewerControls.h; the frame is shown by FramePresenter, the overlay by TextOverlay;
// --record writes the flight as a camera path (scene/CameraPath.h).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "render/RenderTypes.h"
#include "scene/Cloudscape.h"
#include "scene/Scene.h"

namespace cloudlut::view {

struct ViewerOptions {
  std::vector<std::filesystem::path> lutSets;  // at least one; N cycles through them
  bool particles = false;                      // the scene's particles instead of the cloudscape
  scene::Scene scene;                          // particles (when `particles`)
  scene::CloudscapeScene cloudscape;           // otherwise
  render::RenderSettings settings;             // the window size, the first camera and sun, blending...
  std::string quality = "low";                 // cloudscape grid preset
  float exposure = 5.0f;                       // tone mapping (DisplayToneMap.h)
  std::filesystem::path screenshotDir = ".";
  std::optional<std::filesystem::path> record;  // camera path written on exit
};

// The LUT sets under `dir`: `dir` itself when it holds a manifest.json, else its immediate
// subdirectories that do, in name order (e.g. orders18/ and converged/). FileError naming `dir`
// when there is none.
std::vector<std::filesystem::path> findLutSets(const std::filesystem::path& dir);

// The first free "cloudlut_NNNN.png" in `dir`, counting from `from`; `from` is advanced past it.
std::filesystem::path nextScreenshotPath(const std::filesystem::path& dir, int& from);

// Opens the window and runs until Esc or the window is closed; returns 0. NoWindowError
// (WindowContext.h) without a display or a 4.5 core context; FileError for unreadable tables.
int runViewer(const ViewerOptions& options);

}  // namespace cloudlut::view
