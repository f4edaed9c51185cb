#pragma once
// The particle renderer (seed §4.4, §5.4): each particle's bounding box is rasterised, the
// fragment shader intersects the view ray with the ellipsoid and shades it from the tables;
// particles are sorted back to front on the CPU and alpha-blended.
//
// Shading of one particle along one ray (particle space, unit-sphere units; docs/ENGINE_GUIDE.md §2):
//   S, v   entry point and unit direction of the ray mapped into the particle's unit sphere;
//   l      the world sun direction mapped by the particle's inverse transform, renormalised;
//   τ      = ρ · σ · L · T̄, L = 2 cos θv the chord, T̄ the optical-depth table's mean density,
//          σ = extinction_per_m · radius_m of the optical-depth table. The particle's size in
//          the world does not enter: every particle is the reference particle of optical
//          radius σ·ρ (to make a particle of radius r optically as thick as a reference
//          particle of radius R would be, give it ρ·r/R);
//   single = P1(cos θ) · (1 − e^{−τ}) · J̄1(S, v, l, ρ·T̄): the mean source J̄1 (mean sun
//          transmittance) of the homogeneous sphere of the ray's mean density, P1 the single
//          table's "first_phase", cos θ the world-space scattering angle (dir · sun; equal to
//          v·l unless the particle is non-uniformly scaled);
//   multiple = (1 − e^{−τ}) · J̄M(S, v, l, ρ): the ray's own opacity, so that the transparent
//          fringe of a particle does not glow (single/multipleScatteringFromTable decode the tables);
//   ambient  = sky · ambientScale(e^{−τ}, d), d the distance to the first matter as a fraction
//          of the chord (table channel 1): rays that meet matter at once take the full sky
//          light, rays whose matter lies deep along the chord half of it;
//   (both functions: lut_formats/glsl/cloudlut_shading.glsl, shared with the C++ tests)
//   radiance = sunColor · sunlight · (single + multiple) + ambient, sunlight from the light-space
//          occlusion pass (seed §5.3, shaders/occlusion.comp.glsl; 1 when disabled).
// Blending, alpha: back to front, C ← radiance + e^{−τ}·C, T ← e^{−τ}·T. Volume (seed §5.5,
// generalised): per-pixel segment lists resolved exactly (shaders/volume_resolve.comp.glsl).
//
// Cloudscapes (renderCloudscape): particles generated on the GPU from a cloud type and a quality
// preset (render/Cloudscape.h, shaders/cloudscape_generate.comp.glsl), sorted on the GPU
// (bitonic) for alpha blending; rendered at 1/downscale resolution and upscaled with a
// depth-aware (bilateral) filter.
#include <memory>
#include <string>
#include <vector>

#include "io/LutIo.h"
#include "scene/Cloudscape.h"
#include "render/GlContext.h"
#include "scene/Scene.h"

namespace cloudlut::render {

enum Term : unsigned { kTermSingle = 1, kTermMultiple = 2, kTermAmbient = 4, kAllTerms = 7 };

// Pixels whose closest particle is more transparent than this carry no distance.
inline constexpr float kMinOpacityForDistance = 1.0f / 256.0f;
inline constexpr int kMaxImageSide = 16384;
// Occlusion (seed §5.3): extinction scale of the light-space occlusion, and the tile grid.
inline constexpr float kOcclusionXi = 0.05f;
inline constexpr int kLightTiles = 64;
// Volume blending: segments composited exactly per pixel (volume_resolve.comp.glsl), and the
// default size of the fragment node pool per pixel of the particle buffer.
inline constexpr int kMaxSegmentsPerPixel = 32;
inline constexpr int kDefaultFragmentsPerPixel = 16;

enum class BlendMode { Alpha, Volume };
// "alpha" / "volume"; UsageError otherwise.
BlendMode parseBlendMode(const std::string& text);
const char* toString(BlendMode mode);

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
};

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
  double occlusionSeconds = 0;  // light-space tiling, occlusion, smoothing
  double renderSeconds = 0;     // shading + blending: draw (+ volume resolve), glFinish
  double resolveSeconds = 0;    // of which the volume resolve
  double upscaleSeconds = 0;
  double readbackSeconds = 0;
  std::size_t particles = 0;         // drawn
  std::size_t validCells = 0;        // cloudscapes: non-empty cells in the frustum
  std::size_t fragments = 0;         // volume: fragments produced
  std::size_t fragmentOverflow = 0;  // volume: fragments alpha-blended for want of pool room
  std::size_t truncatedPixels = 0;   // volume: pixels with more than kMaxSegmentsPerPixel segments
  std::size_t tileOverflow = 0;      // occlusion: tile-list nodes dropped
};

// Bytes the volume fragment pool needs for a width × height particle buffer.
long double volumePoolBytes(int width, int height, int fragmentsPerPixel);

class Renderer {
 public:
  // Uses the set's "optical_depth", "single_scattering" and "multiple_scattering" tables
  // (FileError naming the directory when one is missing or unusable) and uploads them as 3D
  // textures in their file layout. The context must stay alive and current.
  Renderer(GlContext& context, const io::LutSet& luts);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  Image render(const std::vector<scene::Particle>& particles, const RenderSettings& settings,
               RenderStats* stats = nullptr);

  // A procedural cloudscape, generated on the GPU for the settings' camera.
  Image renderCloudscape(const scene::CloudType& cloud, const scene::QualityPreset& quality, const RenderSettings& settings,
                         RenderStats* stats = nullptr);

  // The GPU generation alone, read back (for tests against generateCloudscapeCpu).
  scene::CpuGeneration generateOnGpu(const scene::CloudType& cloud, const scene::QualityPreset& quality, const RenderSettings& settings);

  // Sunlight reaching each particle after the occlusion pass (same order as `particles`).
  std::vector<float> sunlight(const std::vector<scene::Particle>& particles, const RenderSettings& settings);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Particles sorted back to front: decreasing distance from `eye` to the centre (ties keep
// their order). Returns indices into `particles`.
std::vector<std::size_t> backToFrontOrder(const std::vector<scene::Particle>& particles, const glm::vec3& eye);

}  // namespace cloudlut::render
