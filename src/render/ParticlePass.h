#pragma once
// The particle pass (seed §4.4, §5.4; shaders/particle.vert.glsl, particle.frag.glsl): each
// particle's proxy is rasterised (a polygon around its outline seen from afar, its bounding box
// close by), the fragment shader intersects the view ray with the ellipsoid and shades it from
// the tables (render/Renderer.h gives the shading equations);
// radiance and transmittance are alpha-blended back to front (C ← radiance + e^{−τ}·C,
// T ← e^{−τ}·T) into the float target, the distance to the first matter kept with MIN. In volume
// mode each segment goes to its pixel's fragment list instead (render/VolumeResolve.h), and only
// the fragments that found no room are blended.
#include <cstddef>
#include <map>
#include <string>

#include "io/LutIo.h"
#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuParticleRecord.h"
#include "render/HiddenFragments.h"
#include "render/RenderTypes.h"
#include "render/ShadingTables.h"

namespace cloudlut::render {

class DiffusionVolume;
class SunVolume;

class ParticlePass {
 public:
  // Uploads the tables (ShadingTables: FileError for an unusable set) and builds the program.
  ParticlePass(const GlFunctions& gl, const GlContext& context, const io::LutSet& luts, ParticleBuffers& buffers);
  ~ParticlePass();
  ParticlePass(const ParticlePass&) = delete;
  ParticlePass& operator=(const ParticlePass&) = delete;

  const ShadingTables& tables() const { return tables_; }

  // Whether a volume-blended draw of `count` particles culls hidden fragments (settings.
  // hiddenCulling, at least kHiddenMinParticles): it then wants its records or keys back to front.
  static bool cullsHidden(const RenderSettings& settings, std::size_t count) {
    return settings.blend == BlendMode::Volume && settings.hiddenCulling && count >= kHiddenMinParticles;
  }

  // Empties hidden-fragment culling's per-pixel state for a width × height target (once per frame
  // of volume-aware blending, before its first tile).
  void clearHiddenFragments(int width, int height) { hidden_.clear(width, height); }

  // Draws the first `count` records into the bound target of width × height pixels (the
  // settings' camera, with the projection's far plane at `farPlane` and its near plane at
  // 1e-6 · farPlane): in the order of the sorted keys when `useOrder`, else in record order.
  // `volume`: the fragment lists are bound (VolumeResolve::prepare) and receive the segments;
  // when cullsHidden, the order is reversed (the records or keys are to be back to front) and
  // fragments hidden behind the segments stored before them are not shaded (HiddenFragments.h;
  // the target's depth buffer is used).
  // `sun`: the sun optical-depth volume of this frame when `sunBuilt` (else every point is
  // unshadowed by it). `zenith`: the zenith optical-depth volume (vertical columns) when
  // `zenithBuilt`, for the cloud lighting's ambient under a sky from above (else no cloud lies
  // above or below any point). A particle's own chords come from the sun volume's chord map
  // when it holds them all and the settings want it (sunChordMap), else the shader computes
  // them. The diffusion volume's field, when built, takes settings.diffusionShare of the multiple
  // light. Waits for the GPU (glFinish).
  void draw(std::size_t count, bool useOrder, bool volume, float farPlane, int width, int height,
            const RenderSettings& settings, const SunVolume& sun, bool sunBuilt, const SunVolume& zenith,
            bool zenithBuilt, const DiffusionVolume& diffusion);

  // The fragments `draw` would store, counted per pixel: the same proxies and the same ray test
  // (shaders/particle_chord.glsl), each fragment adding 1 to the red channel of the bound
  // target's colour attachment (blended ONE/ONE; clear it to 0 first), the distance attachment
  // left as it was. Volume-aware blending plans its tiles from them (VolumeResolve::planBands).
  // Waits for the GPU.
  void countFragments(std::size_t count, bool useOrder, float farPlane, int width, int height,
                      const RenderSettings& settings);

 private:
  // The proxies' vertex-stage uniforms (particle.vert.glsl) and buffers, and the vertex array.
  void bindProxies(const ProgramUniforms& uniforms, bool useOrder, float farPlane, int width, int height,
                   const RenderSettings& settings);
  // The particle program compiled for one configuration (particle.frag.glsl's PARTICLE_*
  // #defines, e.g. "PARTICLE_LIGHTING 1"; SUN_CHORD_MAP 1 to read the sun volume's chord map,
  // 0 to compute the chords), linked when first asked for and kept.
  const GlProgram& programFor(const std::string& defines);

  const GlFunctions& gl_;
  ParticleBuffers& buffers_;
  ShadingTables tables_;
  std::map<std::string, GlProgram> programs_;  // by their #defines
  HiddenFragments hidden_;
  GlProgram countProgram_;                      // countFragments', linked on first use
  GLuint vao_ = 0;
};

}  // namespace cloudlut::render
