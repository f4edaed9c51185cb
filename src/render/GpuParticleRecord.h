#pragma once
// The per-particle record on the GPU, one layout for every program that reads or writes
// particles (shaders/particle_common.glsl, std430: seven vec4): the explicit particles packed
// here, the particles the cloudscape generator writes (shaders/cloudscape_generate.comp.glsl),
// read by the particle pass, the light occlusion pass and the ray marcher.
//
//   centerDensity  xyz the centre (world units), w the density scale ρ;
//   toParticle[c]  column c of (R·diag(radii))⁻¹ (p = toParticle · (x − centre), p in the unit
//                  sphere); w: [0] |toParticle · l|, l the unit direction toward the sun:
//                     unit-sphere length per world length along l (the extinction scale of
//                     shadow rays),
//                     [1] bounding-sphere radius, 1.0001 · max radius (world units; a conservative
//                         reject test never clips the surface),
//                     [2] sunlight reaching the particle (1 until the occlusion pass writes it);
//   toWorld[c]     column c of R·diag(radii) (world offset = toWorld · p);
//                  w: the grid identity of a generated particle, exact integers stored as floats
//                     (0 for explicit particles): [0] ring · kGridLayerLimit + layer,
//                     [1] cell x, [2] cell z.
// The ray marcher reads the first four vec4 only.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/GlFunctions.h"
#include "render/GpuStorage.h"
#include "scene/Cloudscape.h"
#include "scene/Scene.h"

namespace cloudlut::render {

struct GpuParticleRecord {
  float centerDensity[4];
  float toParticle[3][4];
  float toWorld[3][4];
};
static_assert(sizeof(GpuParticleRecord) == 7 * 16, "GpuParticleRecord is seven vec4 (particle_common.glsl)");

// Layers per cell the grid identity can tell apart, and the rings it can hold with every
// identity an exact float (ring · limit + layer < 2^24).
inline constexpr int kGridLayerLimit = 256;
inline constexpr int kGridRingLimit = (1 << 24) / kGridLayerLimit;
static_assert(static_cast<long long>(kGridRingLimit) * kGridLayerLimit <= (1LL << 24),
              "grid identities must be exact in a float");

// The record of an explicit particle under a sun toward `sunDirection` (unit): sunlight 1, grid
// identity 0.
GpuParticleRecord packParticle(const scene::Particle& particle, const glm::vec3& sunDirection);

// A generated particle read back: its shape from the record (radii and the reference particle's
// rotation; the ellipsoid itself is not turned) and its grid identity (the
// level-of-detail weight is not stored, the generator folds it into density and size; it is
// recomputed from the identity with the same grid function, scene/glsl/cloudscape_grid.glsl).
scene::GridParticle unpackGridParticle(const GpuParticleRecord& record, const scene::GridParameters& grid,
                                       const glm::vec3& eye);

// The #defines the GLSL record needs: GRID_LAYER_LIMIT, and PARTICLE_RECORD_TEXELS (vec4 per
// record, for shaders that read the records as a buffer texture).
std::string particleRecordDefines();

// GlError naming `what` unless the linked program's Particles block lays records out as
// GpuParticleRecord does (array stride, offset of toWorld).
void requireParticleRecordLayout(const GlFunctions& gl, GLuint program, const std::string& what);

// The particle records (binding 0) and the back-to-front sort keys (binding 1, uvec2 of distance
// bits and record index) that the passes share.
struct ParticleBuffers {
  explicit ParticleBuffers(const GlFunctions& gl) : records(gl), sortKeys(gl) {}
  StorageBuffer records;
  StorageBuffer sortKeys;
  static constexpr GLuint kRecordsBinding = 0;
  static constexpr GLuint kSortKeysBinding = 1;
  static constexpr std::size_t kSortKeyBytes = 8;

  // The first `count` records, copied back from the GPU.
  std::vector<GpuParticleRecord> readRecords(std::size_t count) const;
  // The record indices of the first `count` sort keys, copied back from the GPU.
  std::vector<std::uint32_t> readKeyIndices(std::size_t count) const;
};

}  // namespace cloudlut::render
