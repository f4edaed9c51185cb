#pragma once
// Hidden-fragment culling for volume-aware blending (shaders/hidden_fragments.glsl): the particle
// pass draws front to back and keeps, per pixel, the optical depth τ_front of the segments it has
// stored so far (a sum) and the farthest exit D among them (a maximum). Every stored segment ends
// before D and extinctions add where segments overlap, so the transmittance from the eye to D is
// at most e^{−τ_front}. Once τ_front ≥ −ln kHiddenTransmittance, a later fragment that enters at
// or beyond D adds at most kHiddenTransmittance of its radiance to the pixel: it is not shaded.
//
// On llvmpipe a fragment discarded inside the shader costs what a shaded one does (its lanes run
// masked), so the pass also rejects hidden fragments before the shader: it draws the particles in
// kHiddenBatches batches, and between two it writes each hidden pixel's D into the depth buffer
// (fillDepth). The proxies of the next batch are rasterised at the depth of their particle's
// nearest point (particle.vert.glsl), and the early depth test drops the ones behind D.
//
// The sum and the maximum are atomics, and a fragment reads the sum before the maximum and
// writes the maximum before the sum, so the pair stays conservative whatever the fragments'
// order (the image is exact to kHiddenTransmittance of the farther radiance in any order; which
// fragments are dropped depends on the order, fixed on llvmpipe).
#include <cstddef>
#include <string>

#include "render/GlFunctions.h"
#include "render/GlResources.h"

namespace cloudlut::render {

// What a hidden fragment may still add: at most this share of its radiance (dimensionless).
inline constexpr float kHiddenTransmittance = 1e-3f;
// Batches of the particle pass between which the depth buffer learns the hidden distances.
inline constexpr int kHiddenBatches = 4;
// Fewer particles than this are drawn without culling: their lists are short, and the batches'
// depth passes and the atomics cost more than they save (`one-rho4`: 43–50 → 66–78 ms a
// frame).
inline constexpr std::size_t kHiddenMinParticles = 16;

// Whether culling pays for an explicit scene whose particles' screen rectangles hold at most
// `fragmentBound` fragments (scene::pixelFootprintBound) on a target of `pixels`: only above one
// fragment a pixel on average. Below it the lists are short and culling finds little: the
// bench's 40-particle `cloudscape` stores 212 731 of 219 353 fragments with it. (A generated
// cloudscape, whose bound is unknown, always culls.)
inline bool hiddenCullingPays(std::size_t fragmentBound, std::size_t pixels) { return fragmentBound > pixels; }

class HiddenFragments {
 public:
  explicit HiddenFragments(const GlFunctions& gl);
  ~HiddenFragments();
  HiddenFragments(const HiddenFragments&) = delete;
  HiddenFragments& operator=(const HiddenFragments&) = delete;

  // The #defines of the programs that read or write the per-pixel state (HIDDEN_OPTICAL_DEPTH,
  // FRONT_TAU_UNIT).
  static std::string defines();

  // Sizes the per-pixel state for a width × height target and empties it (nothing hidden). Once
  // per frame, before the first tile is drawn.
  void clear(int width, int height);
  // Binds the state to image units 2 (D) and 3 (τ_front) for the particle program.
  void bind() const;
  // Writes depth = D · depthScale (clamped to [0, 1]; 1 where τ_front < −ln
  // kHiddenTransmittance) into the bound target's depth buffer under the current scissor, colour
  // untouched. It leaves its own program and raster state (colour writes off, depth test ALWAYS
  // with writes, no blending, no face culling): the caller re-applies its own.
  void fillDepth(float depthScale);

 private:
  const GlFunctions& gl_;
  GlProgram depthProgram_;  // linked on first use
  GLuint frontExit_ = 0, frontTau_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace cloudlut::render
