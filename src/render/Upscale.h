#pragma once
// Edge-preserving (bilateral) upscale of the low-resolution particle image (seed §5.4;
// shaders/upscale.comp.glsl, which states the filter): each output pixel blends the four nearest
// low-resolution samples with bilinear weights times a depth similarity to the nearest sample
// (distance to the first matter), so that a cloud's edge against the sky or against a farther
// cloud stays sharp; it takes the nearest sample's distance. The result is written in the
// layout of an Image (rows top first, A = 1 − transmittance, +∞ where there is no distance) into
// storage buffers, so that reading it back is one copy.
#include <cstddef>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuStorage.h"
#include "render/RenderTypes.h"

namespace cloudlut::render {

class Upscale {
 public:
  Upscale(const GlFunctions& gl, const StorageBudget& budget);

  // Filters `low` (radiance + transmittance, distance) into a width × height image on the GPU.
  // Waits for the GPU.
  void run(const FloatRenderTarget& low, int width, int height);
  // The image of the last run.
  Image readBack() const;

  // Work groups of kGroupSize output pixels along a row (on llvmpipe, row-shaped groups run the
  // filter about twice as fast as 8 × 8 tiles).
  static constexpr unsigned kGroupSize = 64;

 private:
  const GlFunctions& gl_;
  const StorageBudget& budget_;
  GlProgram program_;
  StorageBuffer colour_, distance_;  // RGBA and distance per output pixel, rows top first
  int width_ = 0, height_ = 0;
};

}  // namespace cloudlut::render
