#pragma once
// What a render of the particle renderer takes and gives: its settings, the image (radiance,
// opacity, distance to the first matter) and the time and counts of its passes.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "scene/Scene.h"

namespace cloudlut::render {

enum Term : unsigned { kTermSingle = 1, kTermMultiple = 2, kTermAmbient = 4, kAllTerms = 7 };

// Pixels whose closest particle is more transparent than this carry no distance.
inline constexpr float kMinOpacityForDistance = 1.0f / 256.0f;
inline constexpr int kMaxImageSide = 16384;
// Occlusion (seed §5.3): extinction scale of the light-space occlusion, and the tile grid
// (at least kLightTiles × kLightTiles tiles, more for many particles; render/LightOcclusion.h).
inline constexpr float kOcclusionXi = 0.05f;
inline constexpr int kLightTiles = 64;
// Volume blending: segments composited exactly per chunk of a pixel's depth-ordered list
// (render/VolumeResolve.h; pixels with more take ⌈count / kMaxSegmentsPerPixel⌉ chunks), and the
// default size of the fragment node pool per pixel of the particle buffer.
inline constexpr int kMaxSegmentsPerPixel = 32;
// Lists of at most this many segments are resolved by fixed sorting networks without arrays in
// memory (render/VolumeResolve.h), the longer ones in chunks of kMaxSegmentsPerPixel; both
// composite such a list in one exact sweep.
inline constexpr int kShortListCapacity = 32;
// The sorted resolves' segments: lists of up to 4, 8, 16 and 32 (kShortListCapacity); stage r
// takes 4·2^r.
inline constexpr std::array<int, 4> kSortedResolveSlots = {4, 8, 16, kShortListCapacity};
inline constexpr int kDefaultFragmentsPerPixel = 16;

// How volume-aware blending plans its screen tiles when the expected load (fragmentsPerPixel)
// needs more than one (render/VolumeResolve.h): from that load alone (Expected), or from the
// fragments counted first (Counted: a pass of the particles' proxies that runs only their ray
// test, 14% of the particle pass's time on the 1419-particle patch, after which a tile overflows
// only where one row alone holds more fragments than the pool). Auto counts first for generated
// cloudscapes, whose fragments crowd toward the horizon, so that the expected load's tiles
// overflow there and their first draws are shaded for nothing; explicit particle lists count
// first in a Renderer's first frame and while the last count found the expected plan too small,
// unless the particles' screen rectangles (scene::pixelFootprintBound) fit one tile's pool, and
// otherwise at a tile's first overflow, the rows not drawn yet (VolumeResolve::run), so that a
// scene that never overflows pays at most one count (docs/BENCHMARKS.md, "Screen tiles of a
// cloudscape"). Expected never counts: an overflowed tile is split in halves, drawn again.
enum class VolumeTilePlan { Auto, Counted, Expected };
// "auto" / "counted" / "expected"; UsageError otherwise.
VolumeTilePlan parseVolumeTilePlan(const std::string& text);

enum class BlendMode { Alpha, Volume };
// "alpha" / "volume"; UsageError otherwise.
BlendMode parseBlendMode(const std::string& text);
const char* toString(BlendMode mode);

// The lighting model of the particle pass (docs/LIGHTING.md):
//   Seed   seed §4.4 and §5.3 as published: sunlight per particle from the light-space
//          occlusion, multiple scattering of the particle's own sphere at its density ρ, ambient
//          scaled by the crease factor (first matter);
//   Cloud  light that flows through the cloud: sunlight per shading point from the sun
//          optical-depth volume, multiple scattering blending the particle's own sphere at the
//          ray's density ρ·T̄ with the sphere of the cloud around the point (its column toward
//          and away from the sun), ambient (1 − e^{−τ}) times the field of the sky above and the
//          ground below through the cloud above and below the point (cloudlut_shading.glsl).
enum class LightingModel { Seed, Cloud };
// Where the sunlight reaching a particle is evaluated: once per particle (seed §5.3, the
// occlusion pass) or per shading point (the sun optical-depth volume).
enum class SunlightModel { Particle, Volume };
// "seed" / "cloud", "particle" / "volume"; UsageError naming `option` otherwise.
LightingModel parseLighting(const std::string& text, const std::string& option = "--lighting");
SunlightModel parseSunlight(const std::string& text, const std::string& option = "--sunlight");
const char* toString(LightingModel lighting);
const char* toString(SunlightModel sunlight);

struct RenderSettings {
  int width = 640;
  int height = 360;
  scene::View view;
  unsigned terms = kAllTerms;
  BlendMode blend = BlendMode::Alpha;
  int downscale = 1;            // particles rendered at 1/downscale resolution (1, 2 or 4), then upscaled
  bool occlusion = true;        // light-space occlusion (sunlight 1 otherwise)
  bool smoothOcclusion = true;  // its density-weighted smoothing pass
  int fragmentsPerPixel = kDefaultFragmentsPerPixel;  // volume: node pool size per low-res pixel
  long double volumePoolBytes = 0;  // volume: budget of one tile's node pool (0: the default; VolumeResolve.h)
  VolumeTilePlan tilePlan = VolumeTilePlan::Auto;  // volume: how the screen tiles are planned
  // volume: the longest list resolved by a sorting network, 0 … kShortListCapacity
  // (VolumeResolve.h; the image is the same up to rounding whatever it is, only the time changes)
  int volumeShortList = kShortListCapacity;
  // volume: fragments behind segments that let through less than 10⁻³ are not shaded
  // (HiddenFragments.h; at least 16 particles, and for a particle list only when their screen
  // rectangles add up to more than the screen); the image changes by at most that share of their
  // radiance
  bool hiddenCulling = true;
  // Particles seen from afar are rasterised as a polygon around their outline, those close by as
  // their bounding box (shaders/particle.vert.glsl); false: every particle as its box. The image
  // is the same up to rounding either way; the polygon gives llvmpipe fewer fragments to discard.
  bool outlinePolygons = true;
  // The sun volume keeps the chords it splatted (SunVolume, shaders/sun_chord_map.glsl) and the
  // particle shader reads them to take each particle's own ramp out; false: the shader computes
  // them again (the same image, slower: for timing).
  bool sunChordMap = true;
  // A frame of explicit particles reuses the light-space volumes (sun, zenith, diffusion) of the
  // frame before when they would be built from the same inputs (render/LightSpaceInputs.h: the
  // particles, the sun, the grids, the solve): the same image, without the light-space passes'
  // time. false: built every frame (the cold frames of the ground-truth suite's timings).
  bool keepLighting = true;
  // Cloud lighting: the share of the multiple light taken from the diffusion volume
  // (render/DiffusionVolume.h, docs/LIGHTING.md; 0: the tables' alone, the pass is skipped;
  // diffusionShareOfMultiple), the sweeps of its solve on each level, the correction cycles that
  // replace the sweeps on the finest (DiffusionVolume::build), and its node spacing in units of the
  // median particle radius. The gain calibrates the diffusion's low bias: 1/0.855, the prototype's
  // −14.5% on the homogeneous ρ = 1 sphere against the converged tables.
  float diffusionShare = 1.0f;
  int diffusionSweeps = 15;
  int diffusionCycles = 3;
  // With keepLighting, a frame whose sun alone moved starts the diffusion solve from the last one
  // and runs this many correction cycles instead of the whole solve (0: the whole solve;
  // DiffusionVolume::build, docs/LIGHTING.md "A moving sun").
  int diffusionWarmCycles = 1;
  float diffusionSpacing = 0.5f;
  float diffusionGain = 1.2f;
  LightingModel lighting = LightingModel::Cloud;
  SunlightModel sunlight = SunlightModel::Volume;
  // With view.lighting.atmosphere: the sky's scattering orders, 1 = single scattering only
  // (--sky-orders 1), 0 = all of them.
  int skyOrders = 0;
  // With view.lighting.atmosphere and a sun volume: light shafts, the clouds' shadow on the air's
  // single scattering of sunlight (shaders/sky_shafts.glsl; --no-light-shafts turns them off).
  bool lightShafts = true;
  // The density's detail noise (seed §5.4, core/DetailNoise.h): the optical depth of each chord
  // times the mean of the density factor along it; amplitude 0 = off.
  DetailNoise detail;

  // The particle buffer's size in pixels: width and height over downscale, rounded up.
  int particleWidth() const { return (width + downscale - 1) / downscale; }
  int particleHeight() const { return (height + downscale - 1) / downscale; }
};

// The sunlight each lighting model takes unless told otherwise.
inline SunlightModel defaultSunlight(LightingModel lighting) {
  return lighting == LightingModel::Seed ? SunlightModel::Particle : SunlightModel::Volume;
}

struct Image {
  int width = 0;
  int height = 0;
  // Row 0 is the top row. Per pixel: linear radiance R, G, B (per unit sun irradiance, sr⁻¹,
  // times the sun colour) and A = 1 − transmittance of all the particles.
  std::vector<float> rgba;
  // Distance from the eye to the first matter of the closest particle at least
  // kMinOpacityForDistance opaque; +infinity where there is none.
  std::vector<float> distance;

  const float* pixel(int x, int y) const { return rgba.data() + 4 * (static_cast<std::size_t>(y) * width + x); }
  float distanceAt(int x, int y) const { return distance[static_cast<std::size_t>(y) * width + x]; }
  // Samples that are NaN or infinite in rgba (distance may hold +infinity by design).
  std::size_t nonFiniteCount() const;
};

// UsageError unless 1 ≤ width, height ≤ kMaxImageSide and the buffers of such an image fit in
// the memory this machine can spare.
void checkImageSize(long long width, long long height);

struct RenderStats {
  double uploadSeconds = 0;     // particle buffer upload (explicit particles)
  double generateSeconds = 0;   // GPU generation + sort (cloudscapes)
  double occlusionSeconds = 0;  // light-space tiling, occlusion, smoothing; the sun volume
  bool lightSpaceKept = false;  // the light-space volumes were the frame before's (keepLighting)
  bool lightSpaceSunOnly = false;  // only the sun moved: its volume rebuilt, the zenith and diffusion
                                   // column volumes kept (keepLighting, reusableUnderMovedSun)
  bool diffusionWarm = false;      // the diffusion solve started from the frame before's (diffusionWarmCycles)
  double renderSeconds = 0;     // shading + blending: draw (+ volume resolve), glFinish
  double resolveSeconds = 0;    // of which the volume resolves
  double upscaleSeconds = 0;    // bilateral upscale (GPU), glFinish
  double readbackSeconds = 0;   // the final image to the CPU
  double skySeconds = 0;        // the atmosphere's sky pass (render/SkyPass.h), when the sky is the atmosphere
  std::size_t particles = 0;         // drawn
  std::size_t validCells = 0;        // cloudscapes: non-empty cells within the far distance
  std::size_t litParticles = 0;      // cloudscapes: particles the light-space passes took (in view or not)
  std::size_t fragments = 0;         // volume: fragments produced
  std::size_t fragmentOverflow = 0;  // volume: fragments alpha-blended for want of pool room
  std::size_t truncatedPixels = 0;   // volume: pixels resolved in more than one chunk of kMaxSegmentsPerPixel
  std::size_t midListPixels = 0;     // volume: pixels with more than min(8, volumeShortList) segments
  std::size_t longListPixels = 0;    // volume: pixels with more than volumeShortList segments
  std::size_t resolveCutPixels = 0;  // volume: pixels whose resolve the GL cut short (VolumeResolve.h)
  std::size_t volumeTiles = 0;       // volume: screen tiles, each drawn and resolved on its own
  std::size_t volumeRedrawnTiles = 0;  // volume: tiles over the pool's room, undone and split in two
  std::size_t countedFragments = 0;  // volume: fragments counted to plan the tiles (VolumeTilePlan)
  bool volumeTilesCounted = false;   // volume: the tiles were planned from countedFragments
  std::size_t fragmentBound = 0;     // explicit particles: scene::pixelFootprintBound of the frame
  std::size_t volumePoolBytes = 0;   // volume: bytes of the node pool (one tile's)
  std::size_t tileOverflow = 0;      // occlusion: cover-bin entries dropped (render/LightOcclusion.h)
  std::size_t sunFootprintOverflow = 0;  // sun volume: particle-cascade pairs left to a coarser cascade
  std::size_t sunChordsNeeded = 0;  // sun volume: chords of every footprint (SunVolume::chordsNeeded)
  bool sunChordMap = false;         // sun volume: the chord map held them all and the particle shader read it
  std::size_t rayMarchDroppedPixels = 0;  // ray marcher: pixels whose view or a shadow ray left particles out
  std::size_t rayMarchBudgetPixels = 0;   // ray marcher: pixels whose loops the GL cut short
};

}  // namespace cloudlut::render
