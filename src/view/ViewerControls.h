#pragma once
// What the viewer's keys, mouse and scroll wheel change (README, "cloudlut view", lists them):
// the camera, the sun and the render settings of the next frame. Pure state changes, so that
// they can be tested without a window; the window's callbacks (Viewer.cpp) feed them GLFW's key
// codes.
#include <cstddef>
#include <string>
#include <vector>

#include "render/RenderTypes.h"
#include "view/FlyCamera.h"

namespace cloudlut::view {

inline constexpr float kTurnStepDeg = 2.5f;      // arrow keys: per press or key repeat
inline constexpr float kSunStepDeg = 5.0f;       // sun keys: per press or key repeat
inline constexpr float kDragDegPerPixel = 0.2f;  // mouse drag: per window pixel
inline constexpr float kSpeedStep = 1.25f;       // scroll: flying speed factor per notch

struct ViewerState {
  FlyCamera camera;
  SunAngles sun;
  float speed = 300.0f;  // world units (metres) per second
  std::size_t quality = 0;  // index into scene::qualityPresetNames()
  render::BlendMode blend = render::BlendMode::Volume;
  unsigned terms = render::kAllTerms;
  bool occlusion = true;
  int downscale = 1;
  std::size_t lutSet = 0, lutSetCount = 1;  // which of the LUT sets found (N cycles)
  bool overlay = true;
  // Requests the loop acts on.
  bool quit = false;
  int screenshots = 0;
};

// Keys held down at the start of a frame: continuous motion.
struct HeldKeys {
  bool forward = false, back = false, left = false, right = false, down = false, up = false;
};

// A key press or repeat (GLFW key code and modifier bits); other actions are ignored.
void onKey(ViewerState& state, int key, int action, int mods);
// Scroll by `notches`: speed × kSpeedStep^notches, within [1, 1e5].
void onScroll(ViewerState& state, double notches);
// Mouse drag by (dx, dy) window pixels: looks around (drag right looks right, drag up looks up)
// or, with `moveSun`, turns the sun the same way.
void onDrag(ViewerState& state, double dx, double dy, bool moveSun);
// Moves the camera for `seconds` at state.speed along the held keys.
void advance(ViewerState& state, const HeldKeys& keys, double seconds);

// One line per control, for --help and the overlay's help page.
std::vector<std::string> controlsHelp();

}  // namespace cloudlut::view
