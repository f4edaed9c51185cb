#include "view/ViewerControls.h"

#include <algorithm>
#include <cmath>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "scene/Cloudscape.h"

namespace cloudlut::view {

void onKey(ViewerState& s, int key, int action, int mods) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  const bool press = action == GLFW_PRESS;
  switch (key) {
    case GLFW_KEY_LEFT: s.camera.turn(kTurnStepDeg, 0.0f); return;
    case GLFW_KEY_RIGHT: s.camera.turn(-kTurnStepDeg, 0.0f); return;
    case GLFW_KEY_UP: s.camera.turn(0.0f, kTurnStepDeg); return;
    case GLFW_KEY_DOWN: s.camera.turn(0.0f, -kTurnStepDeg); return;
    case GLFW_KEY_J: s.sun.turn(-kSunStepDeg, 0.0f); return;
    case GLFW_KEY_L: s.sun.turn(kSunStepDeg, 0.0f); return;
    case GLFW_KEY_I: s.sun.turn(0.0f, kSunStepDeg); return;
    case GLFW_KEY_K: s.sun.turn(0.0f, -kSunStepDeg); return;
    default: break;
  }
  if (!press) return;  // the switches below act once per press
  const std::size_t qualities = scene::qualityPresetNames().size();
  switch (key) {
    case GLFW_KEY_ESCAPE: s.quit = true; break;
    case GLFW_KEY_F12: ++s.screenshots; break;
    case GLFW_KEY_1: case GLFW_KEY_2: case GLFW_KEY_3:
      s.quality = std::min<std::size_t>(static_cast<std::size_t>(key - GLFW_KEY_1), qualities - 1);
      break;
    case GLFW_KEY_B:
      s.blend = s.blend == render::BlendMode::Alpha ? render::BlendMode::Volume : render::BlendMode::Alpha;
      break;
    case GLFW_KEY_Z: s.terms ^= render::kTermSingle; break;
    case GLFW_KEY_X: s.terms ^= render::kTermMultiple; break;
    case GLFW_KEY_C: s.terms ^= render::kTermAmbient; break;
    case GLFW_KEY_O: s.occlusion = !s.occlusion; break;
    case GLFW_KEY_G: s.downscale = s.downscale == 4 ? 1 : 2 * s.downscale; break;
    case GLFW_KEY_N: s.lutSet = (s.lutSet + 1) % std::max<std::size_t>(s.lutSetCount, 1); break;
    case GLFW_KEY_H: s.overlay = !s.overlay; break;
    default: break;
  }
  (void)mods;
}

void onScroll(ViewerState& s, double notches) {
  s.speed = std::clamp(s.speed * std::pow(kSpeedStep, static_cast<float>(notches)), 1.0f, 1e5f);
}

void onDrag(ViewerState& s, double dx, double dy, bool moveSun) {
  const float yaw = -kDragDegPerPixel * static_cast<float>(dx), pitch = -kDragDegPerPixel * static_cast<float>(dy);
  if (moveSun)
    s.sun.turn(-yaw, pitch);
  else
    s.camera.turn(yaw, pitch);
}

void advance(ViewerState& s, const HeldKeys& k, double seconds) {
  const float d = s.speed * static_cast<float>(seconds);
  const auto axis = [](bool plus, bool minus) { return static_cast<float>(plus) - static_cast<float>(minus); };
  s.camera.move(d * axis(k.forward, k.back), d * axis(k.up, k.down), d * axis(k.right, k.left));
}

std::vector<std::string> controlsHelp() {
  return {"mouse drag, arrow keys   look around",
          "W A S D                  move",
          "Q E                      down / up",
          "scroll                   flying speed",
          "I K J L, shift + drag    sun elevation / azimuth",
          "1 2 3                    quality low / medium / high",
          "B                        blending alpha / volume",
          "Z X C                    single / multiple / ambient term on or off",
          "O                        sunlight: light-space occlusion on or off",
          "G                        render at 1, 1/2, 1/4 resolution",
          "N                        next LUT set (e.g. 18 orders / converged)",
          "H                        overlay on or off",
          "F12                      screenshot cloudlut_NNNN.png",
          "Esc, closing the window  quit"};
}

}  // namespace cloudlut::view
