#pragma once
// The ray-marched baseline (seeds 000 and 003) on a particle list, on the GPU (one fragment per
// pixel, OpenGL 4.5 through the same headless context as the particle renderer). It renders the
// medium of reference/ScenePathTracer.h — overlapping particles whose densities add, particle i
// of density ρ_i·ρ̂(p) with ρ̂ the reference particle's density model, extinction β·R·ρ_i·ρ̂ in
// the particle's unit-sphere units (|M_i⁻¹ω| per world unit along ω) — so that its error against
// the path-traced ground truth measures the marching and lighting approximations alone.
//
// Per pixel (shaders/raymarch.frag.glsl):
//   - the particles on the view ray are found (ellipsoid intervals) through a uniform grid of
//     particle lists (render/ParticleCellGrid.h, shaders/raymarch_cells.glsl), the nearest
//     kMaxViewHits kept in order of entry; the march covers either
//     their whole extent in `steps` equal steps (fixed) or only the union of the intervals, the
//     `steps` spread over the occupied length (adaptive: empty space skipped), sampled at each
//     step's midpoint;
//   - Beer–Lambert transmittance and Hillaire's energy-conserving step integral: with σ constant
//     over a step of length h and albedo 1, ∫ T·σ·S = T·S·(1 − e^{−σh}); then T ← T·e^{−σh};
//   - the sun's source term at a step: a shadow ray toward the sun over the particles it crosses
//     (found through the same grid, the nearest kMaxShadowHits kept), `shadowSteps` midpoint
//     steps to the farthest exit, optical depth τ; Wrenninge's octaves
//       S_sun = sunColor · Σ_{i<octaves} b^i · p_i(cos θ) · e^{−a^i τ},
//     a attenuating the extinction, b the contribution, c the anisotropy: p_0 = P1 (the first
//     phase function), p_i = PM with g·c^i for HG/Cornette–Shanks (a blend toward isotropic
//     with weight c^i for Jendersie–d'Eon);
//   - ambient: a uniform sky in-scattered unshadowed, S_sky = skyColor (exact for a
//     non-absorbing medium lit by a uniform sky: it yields sky·(1 − T));
//   - the march stops when T < minTransmittance.
// Output as the particle renderer's Image: RGB radiance, A = 1 − T, distance to the first point
// at least kMinOpacityForDistance opaque. RenderStats counts the pixels that left particles out
// (rayMarchDroppedPixels) and those whose loops the GL cut short (rayMarchBudgetPixels):
// llvmpipe ends every loop of a shader invocation once its loops have made 65535 passes in all
// (an invocation shades several pixels). Before the grid, every shadow ray tested every
// particle, and a 1419-particle scene at 64 steps lost whole pixels to that limit, silently.
#include <memory>
#include <vector>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/ReferenceParticle.h"
#include "render/GlContext.h"
#include "render/RenderTypes.h"
#include "scene/Scene.h"

namespace cloudlut::render {

// The most particles kept on a view ray and on a shadow ray (shaders/raymarch_cells.glsl).
inline constexpr int kMaxViewHits = 48;
inline constexpr int kMaxShadowHits = 24;

struct RayMarchSettings {
  int width = 640;
  int height = 360;
  scene::View view;
  unsigned terms = kAllTerms;      // single = octave 0, multiple = octaves ≥ 1, ambient
  int steps = 64;                  // view-ray steps (1 … 4096)
  bool adaptive = false;           // skip empty space, steps spread over the occupied length
  int shadowSteps = 6;             // steps of each shadow ray (1 … 256)
  int octaves = 8;                 // Wrenninge octaves (1 … 16; 1 = single scattering only)
  float a = 0.5f, b = 0.5f, c = 0.5f;  // octave attenuation of extinction, contribution, anisotropy
  Phase first = defaults::kFirstPhase;  // P1
  Phase later = defaults::kLaterPhase;  // PM
  float unitOpticalRadius = static_cast<float>(defaults::kUnitOpticalRadius);  // β·R
  float minTransmittance = 1e-4f;
};

class RayMarchRenderer {
 public:
  // Uploads the density model (a 3D texture for the gridded models). The context must stay
  // alive and current.
  RayMarchRenderer(GlContext& context, const ReferenceParticle& model);
  ~RayMarchRenderer();
  RayMarchRenderer(const RayMarchRenderer&) = delete;
  RayMarchRenderer& operator=(const RayMarchRenderer&) = delete;

  // UsageError for settings outside the ranges above.
  Image render(const std::vector<scene::Particle>& particles, const RayMarchSettings& settings,
               RenderStats* stats = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cloudlut::render
