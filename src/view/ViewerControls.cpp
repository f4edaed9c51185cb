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
    case GLFW_KEY_M:
      s.lighting = s.lighting == render::LightingModel::Cloud ? render::LightingModel::Seed : render::LightingModel::Cloud;
      s.sunlight = render::defaultSunlight(s.lighting);
      break;
    case GLFW_KEY_P:
      s.sunlight = s.sunlight == render::SunlightModel::Volume ? render::SunlightModel::Particle
                                                               : render::SunlightModel::Volume;
      break;
    case GLFW_KEY_G: s.downscale = s.downscale == 4 ? 1 : 2 * s.downscale; break;
    case GLFW_KEY_N: s.lutSet = (s.lutSet + 1) % std::max<std::size_t>(s.lutSetCount, 1); break;
    case GLFW_KEY_H: s.overlay = !s.overlay; break;
    case GLFW_KEY_V: s.detail = !s.detail; break;
    case GLFW_KEY_F: s.diffusion = !s.diffusion; break;
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

namespace {

int motionIndex(int key) {
  switch (key) {
    case GLFW_KEY_W: return 0;
    case GLFW_KEY_S: return 1;
    case GLFW_KEY_A: return 2;
    case GLFW_KEY_D: return 3;
    case GLFW_KEY_Q: return 4;
    case GLFW_KEY_E: return 5;
    default: return -1;
  }
}

}  // namespace

void MotionKeys::onKey(int key, int action, double seconds) {
  const int i = motionIndex(key);
  if (i < 0) return;
  if (action == GLFW_PRESS && pressedAt_[i] < 0) pressedAt_[i] = seconds;
  if (action == GLFW_RELEASE && pressedAt_[i] >= 0) {
    held_[i] += std::max(seconds - pressedAt_[i], kTapSeconds);
    pressedAt_[i] = -1;
  }
}

HeldSeconds MotionKeys::take(double seconds) {
  double t[kKeys];
  for (int i = 0; i < kKeys; ++i) {
    t[i] = held_[i];
    if (pressedAt_[i] >= 0) {  // still held: count up to now, carry on from now
      t[i] += std::max(seconds - pressedAt_[i], 0.0);
      pressedAt_[i] = seconds;
    }
    held_[i] = 0;
  }
  return {t[0], t[1], t[2], t[3], t[4], t[5]};
}

void advance(ViewerState& s, const HeldSeconds& h) {
  const auto d = [&](double plus, double minus) { return s.speed * static_cast<float>(plus - minus); };
  s.camera.move(d(h.forward, h.back), d(h.up, h.down), d(h.right, h.left));
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
          "M                        lighting model cloud / seed (docs/LIGHTING.md)",
          "P                        sunlight per shading point (volume) / per particle",
          "G                        render at 1, 1/2, 1/4 resolution",
          "N                        next LUT set (e.g. 18 orders / converged)",
          "V                        detail noise on or off",
          "F                        diffusion volume on or off (cloud lighting)",
          "H                        overlay on or off",
          "F12                      screenshot cloudlut_NNNN.png",
          "Esc, closing the window  quit"};
}

}  // namespace cloudlut::view
