#pragma once
// Volume-aware blending (seed §5.5, eqs. 10–17, generalised to any number of overlapping
// particles): the per-pixel fragment lists that the particle pass fills (a node pool and an r32ui
// image of list heads; shaders/volume_fragments.glsl) and their exact resolve
// (shaders/volume_resolve.comp.glsl): each pixel's segments are cut at every entry and exit,
// inside each piece the extinctions add and the colours combine weighted by extinction, and the
// pieces are composited front to back. At most kMaxSegmentsPerPixel segments per pixel (the
// nearest) are composited exactly; farther ones, and the fragments that found no room in the pool
// (alpha-blended by the particle pass), are composited behind them.
#include <cstddef>
#include <string>

#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuStorage.h"
#include "render/RenderTypes.h"

namespace cloudlut::render {

// Words (4 bytes) per fragment node: entry, exit, τ, radiance r, g, b, next.
inline constexpr int kFragmentNodeWords = 7;

// Bytes the fragment pool needs for a width × height particle buffer: its four counters and
// fragmentsPerPixel nodes per pixel.
long double volumePoolBytes(int width, int height, int fragmentsPerPixel);

class VolumeResolve {
 public:
  VolumeResolve(const GlFunctions& gl, const StorageBudget& budget);
  ~VolumeResolve();
  VolumeResolve(const VolumeResolve&) = delete;
  VolumeResolve& operator=(const VolumeResolve&) = delete;

  // The #defines of the programs that write or read the lists (FRAGMENT_NODE_WORDS).
  static std::string fragmentDefines();

  // Sizes the pool for a width × height buffer (UsageError beyond the storage budget), empties it
  // and the lists, and binds both for the particle pass (pool at binding 2, heads at image unit 0).
  void prepare(int width, int height, int fragmentsPerPixel);
  // Binds a small pool and a 1×1 head image, for a particle pass that stores no fragments.
  void bindUnused();

  // Composites the lists into the colour texture (RGBA32F, width × height as prepared): in, the
  // fragments that found no room (radiance, transmittance); out, the result.
  void resolve(GLuint colourTexture);

  struct Counts {
    std::size_t fragments = 0;        // produced
    std::size_t overflow = 0;         // alpha-blended for want of pool room
    std::size_t truncatedPixels = 0;  // pixels with more than kMaxSegmentsPerPixel segments
  };
  Counts counts() const;

  static constexpr int kGroupSide = 8;  // work groups of kGroupSide² pixels

 private:
  const GlFunctions& gl_;
  const StorageBudget& budget_;
  GlProgram program_;
  StorageBuffer pool_;
  GLuint heads_ = 0, unusedHeads_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace cloudlut::render
