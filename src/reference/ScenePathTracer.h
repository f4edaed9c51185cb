#pragma once
// Monte Carlo ground truth for a particle scene (`cloudlut reference scene`): a path tracer of
// the exact medium the particle list describes, independent of the tables and of every
// renderer. It shares with them only the density model (core/ReferenceParticle), the phase
// functions (core/Glsl.h) and the conventions below.
//
// The medium. Particle i maps its unit sphere p to the world by x = c_i + M_i·p. Its density
// is ρ_i·ρ̂(p) with ρ̂ the reference particle's normalised density (the same model, seed and
// grid as the optical-depth table). Densities of overlapping particles add. As in the renderer
// (docs/SCENE_FORMAT.md), lengths are measured in each particle's own unit-sphere units, so a
// particle's world size does not change its thickness: a ray of unit world direction ω meets
// the extinction
//     σ_i(x, ω) = β·R · ρ_i · ρ̂(M_i⁻¹(x − c_i)) · |M_i⁻¹ ω|        (world units⁻¹)
// in particle i (β·R = the unit optical radius). For a sphere of any radius the medium is the
// ordinary isotropic one (σ = β·R·ρ·ρ̂ / r); a stretched particle is the reference particle
// seen through its linear map (optical lengths along every line are those of the unit-sphere
// problem), with phase functions evaluated at world-space scattering angles, as the renderer
// does. No absorption (single-scattering albedo 1).
//
// Detail noise (optional, SceneMedium::detail): the summed density at the world point x is
// multiplied by m(x) = 1 + a·n(x/s) ∈ [1 − a, 1 + a] (lut_formats/glsl/cloudlut_detail_noise.glsl).
//
// Light: a directional sun (unit irradiance, times the sun colour) along −l, and optionally a
// sky (times the sky colour): radiance 1 from every direction above the horizon (a direction ω
// with ω.y ≥ 0, world +y up) and SceneLight::skyBelow from every direction below it (the
// ground's return; 1, the default, is the uniform sky).
//
// The estimator: backward path tracing from the camera. Free flights by delta tracking against
// a piecewise-constant majorant (the sum of the per-particle majorants β·R·ρ_i·|M_i⁻¹ω| of the
// particles whose ellipsoids the ray crosses; ρ̂ ≤ 1), so every sample is unbiased. Every
// scattering vertex connects to the sun (next-event estimation with the first phase function
// P1 and the sun transmittance by ratio tracking; exact for homogeneous particles); the path
// continues along a direction sampled exactly from the later phase function PM, and a
// continuation that leaves the medium collects the sky. With albedo 1 and exact phase sampling
// the path weight stays 1; paths end when they leave the medium (or at maxOrder). Transmittance
// of the camera ray (alpha = 1 − T) by ratio tracking along it.
//
// Finding the particles a ray crosses: a BVH over the particles' exact bounding boxes
// (reference/ParticleBvh.h) gives the candidates in index order, so the spans, and every sum
// and random draw that follows, are those of the loop over all particles (bruteForce).
//
// Determinism: pixel i draws from McRng(seed, i, 0) and is computed by one thread, so the
// image does not depend on the number of threads.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/Progress.h"
#include "core/ReferenceParticle.h"
#include "reference/SphereMonteCarlo.h"

namespace cloudlut::reference {

struct SceneParticle {
  glm::dvec3 center{0.0};
  glm::dmat3 toParticle{1.0};  // M⁻¹: world offset → unit-sphere coordinates
  double density = 1.0;       // ρ
};

struct SceneMedium {
  std::vector<SceneParticle> particles;
  const ReferenceParticle* model = nullptr;  // ρ̂; must outlive the medium's use
  double unitOpticalRadius = defaults::kUnitOpticalRadius;  // β·R
  // Detail noise (core/DetailNoise.h, DetailNoise::packed()): the extinction at the world point x
  // times m(x) = 1 + a·n(x/s) = glsl::detailDensityFactor(x, detail), the renderer's definition;
  // the majorants times 1 + a. All 0: none (m = 1).
  glm::vec4 detail{0.0f};
};

struct ScenePtSettings {
  Phase first = defaults::kFirstPhase;  // sunlight's first scattering (NEE)
  Phase later = defaults::kLaterPhase;  // every later scattering (path continuation)
  int samplesPerPixel = 64;
  std::uint64_t seed = 1;
  int maxOrder = 0;          // > 0: stop after this many scattering events; 0 = kMaxPathVertices
  bool jitter = false;       // sample the pixel's area (true) or its centre (false)
  double maxSeconds = 0;     // > 0: give up (WorkLimitExceeded) once the wall time passes this
  bool bruteForce = false;   // test every particle per ray instead of the BVH's candidates
                             // (reference/ParticleBvh.h); the same result bit for bit, slower.
                             // Scenes of fewer than kBvhMinParticles particles always use the loop.
};

// Work limits that bound every accepted input. A path ends after kMaxPathVertices scattering
// events even without maxOrder (diffusion needs about τ² of them in a particle of optical radius
// τ; 10⁶ covers τ ≈ 1000); the paths cut there are counted (ScenePtImage::truncatedPaths).
inline constexpr int kMaxPathVertices = 1000000;
// The optical radius β·R·ρ_i of one particle above which its paths (about τ² events each) and
// the null collisions of delta tracking cannot finish in useful time.
inline constexpr double kMaxParticleOpticalRadius = 10000.0;

// Below this many particles the loop over all of them is as fast as the BVH or faster (9
// particles: the BVH 1.4× slower, 36: even, 40: 1.3× faster; docs/BENCHMARKS.md), so the BVH is
// built only from here up. Either way the image is the same.
inline constexpr std::size_t kBvhMinParticles = 32;

// Thrown by renderScene when ScenePtSettings::maxSeconds passes; the message says how much was
// done and estimates the time the whole image would need.
struct WorkLimitExceeded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The first particle whose optical radius β·R·ρ_i (dimensionless) exceeds
// kMaxParticleOpticalRadius, as "particles[i].density: ..."; empty when there is none.
std::string mediumWorkProblem(const SceneMedium& medium);

struct SceneLight {
  glm::dvec3 sunDirection{0.0, 1.0, 0.0};  // unit, toward the sun
  double skyBelow = 1.0;  // sky radiance below the horizon per unit sky radiance above it
};

// Per-ray estimates (means of the samples and their standard errors): radiance per unit sun
// irradiance of order 1 and of orders ≥ 2, radiance per unit sky radiance (above the horizon), and the camera
// ray's transmittance.
struct RayEstimate {
  double single = 0, singleSe = 0;
  double multiple = 0, multipleSe = 0;
  double sky = 0, skySe = 0;
  double transmittance = 1, transmittanceSe = 0;
  double sunSe = 0;      // standard error of single + multiple
  double sunSkyCov = 0;  // covariance of the means of (single + multiple) and sky
  double vertices = 0;   // mean scattering vertices per path
};

// One camera ray (origin outside or inside the medium, unit direction), `samples` paths from
// McRng(seed, stream, 0).
RayEstimate estimateRay(const SceneMedium& medium, const SceneLight& light, const ScenePtSettings& settings,
                        const glm::dvec3& origin, const glm::dvec3& direction, long long samples,
                        std::uint64_t stream);

// The image: pixel (x, y) from the top-left; `cameraRay(px, py, origin, direction)` gives the
// ray through the image point (px, py) in pixel units (centre of pixel (x, y) = (x + .5, y + .5)).
struct ScenePtImage {
  int width = 0, height = 0;
  // Per pixel, row-major from the top: the estimates above.
  std::vector<RayEstimate> pixels;
  double seconds = 0;
  double meanVertices = 0;  // scattering vertices per path
  long long truncatedPaths = 0;  // paths cut at kMaxPathVertices (maxOrder 0): a dark bias
};

using CameraRayFn = std::function<void(double px, double py, glm::dvec3& origin, glm::dvec3& direction)>;

// Parallel over 16×16 tiles (oneTBB); progress reported as the fraction of tiles done.
ScenePtImage renderScene(const SceneMedium& medium, const SceneLight& light, const ScenePtSettings& settings,
                         int width, int height, const CameraRayFn& cameraRay, const ProgressFn& progress = {});

// Exact optical depth along the segment [t0, t1] of a ray (world units) when every particle is
// homogeneous (model Sphere), without the detail noise; used by the tests and the analytic shortcut.
double homogeneousOpticalDepth(const SceneMedium& medium, const glm::dvec3& origin, const glm::dvec3& direction,
                               double t0, double t1);

}  // namespace cloudlut::reference
