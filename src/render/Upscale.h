#pragma once
// Edge-preserving (bilateral) upscale of the low-resolution particle image (seed §5.4;
// shaders/upscale.comp.glsl, which states the filter): each output pixel blends the four nearest
// low-resolution samples with bilinear weights times a depth similarity to the nearest sample
// (distance to the first matter), so that a cloud's edge against the sky or against a farther
// cloud stays sharp; it takes the nearest sample's distance.
#include "render/GlFunctions.h"
#include "render/GlResources.h"

namespace cloudlut::render {

class Upscale {
 public:
  explicit Upscale(const GlFunctions& gl);

  // Filters `low` (radiance + transmittance, distance) into `full`, any sizes. Waits for the GPU.
  void run(const FloatRenderTarget& low, const FloatRenderTarget& full);

  static constexpr int kGroupSide = 8;  // work groups of kGroupSide² output pixels

 private:
  const GlFunctions& gl_;
  GlProgram program_;
};

}  // namespace cloudlut::render
