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
// Shortest time a motion key counts as held: GLFW stamps events when they are polled, once a
// frame, so a tap within a slow frame arrives as a press and a release at the same time.
inline constexpr double kTapSeconds = 0.1;

struct ViewerState {
  FlyCamera camera;
  SunAngles sun;
  float speed = 300.0f;  // world units (metres) per second
  std::size_t quality = 0;  // index into scene::qualityPresetNames()
  render::BlendMode blend = render::BlendMode::Volume;
  unsigned terms = render::kAllTerms;
  bool occlusion = true;
  render::LightingModel lighting = render::LightingModel::Cloud;  // M switches (docs/LIGHTING.md)
  render::SunlightModel sunlight = render::SunlightModel::Volume;  // P switches
  int downscale = 1;
  bool detail = true;  // V: the scene's detail noise on or off (when it has one)
  bool diffusion = true;  // F: the diffusion volume's share of the multiple light on or off
  std::size_t lutSet = 0, lutSetCount = 1;  // which of the LUT sets found (N cycles)
  bool overlay = true;
  // Requests the loop acts on.
  bool quit = false;
  int screenshots = 0;
};

// How long each motion key (W S A D Q E) was held since the last frame, in seconds: motion
// follows the keys' press and release times (a release at least kTapSeconds after its press), so
// that a tap moves the camera even when a frame takes longer than the tap (llvmpipe).
struct HeldSeconds {
  double forward = 0, back = 0, left = 0, right = 0, down = 0, up = 0;
};

class MotionKeys {
 public:
  // A press or release of a GLFW key at time `seconds` (other keys and repeats are ignored).
  void onKey(int key, int action, double seconds);
  // The time held since the previous call (or the first press), up to `seconds`.
  HeldSeconds take(double seconds);

 private:
  static constexpr int kKeys = 6;  // forward, back, left, right, down, up
  double pressedAt_[kKeys] = {-1, -1, -1, -1, -1, -1};  // −1: not held
  double held_[kKeys] = {0, 0, 0, 0, 0, 0};
};

// A key press or repeat (GLFW key code and modifier bits); other actions are ignored.
void onKey(ViewerState& state, int key, int action, int mods);
// Scroll by `notches`: speed × kSpeedStep^notches, within [1, 1e5].
void onScroll(ViewerState& state, double notches);
// Mouse drag by (dx, dy) window pixels: looks around (drag right looks right, drag up looks up)
// or, with `moveSun`, turns the sun the same way.
void onDrag(ViewerState& state, double dx, double dy, bool moveSun);
// Moves the camera at state.speed for as long as each motion key was held:
// eye += speed · ((t_W − t_S)·forward + (t_E − t_Q)·up + (t_D − t_A)·right).
void advance(ViewerState& state, const HeldSeconds& held);

// One line per control, for --help and the overlay's help page.
std::vector<std::string> controlsHelp();

}  // namespace cloudlut::view
