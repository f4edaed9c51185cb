#pragma once
// A uniform grid of cells over the particles' bounding spheres, each cell listing the particles
// whose bounding sphere may reach into it, so that a ray visits only the particles of the cells
// it crosses (shaders/raymarch_cells.glsl walks them in order, Amanatides & Woo's traversal).
// The ray marcher finds the particles on its view and shadow rays through it; without it each
// shadow ray tested every particle, steps × particles tests per pixel.
//
// Layout (compressed rows): cell (x, y, z) is c = (z·dims.y + y)·dims.x + x; its particles are
// indices[cellStart[c] … cellStart[c + 1]). A particle is listed in every cell that the box
// around its bounding sphere overlaps, the box widened by 1% of a cell on each side so that the
// traversal's rounding never finds a particle's entry point in a cell that does not list it.
// The cells are about one median bounding diameter wide, at most kMaxCellsPerAxis per axis, and
// coarsened (halved per axis) until the listing holds at most `maxEntries` indices. Up to
// kCellGridMinParticles particles share one cell: testing them all is as fast as walking cells.
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "render/GpuParticleRecord.h"

namespace cloudlut::render {

inline constexpr int kMaxCellsPerAxis = 64;
inline constexpr std::size_t kCellGridMinParticles = 32;

struct ParticleCellGrid {
  glm::vec3 origin{0.0f};    // world position of the grid's low corner
  glm::vec3 cellSize{1.0f};  // world units per cell along x, y, z
  glm::ivec3 dims{1};        // cells per axis, 1 … kMaxCellsPerAxis
  std::vector<std::uint32_t> cellStart;  // dims.x·dims.y·dims.z + 1 offsets into indices
  std::vector<std::uint32_t> indices;    // record indices, ascending within each cell
  std::size_t cells() const { return static_cast<std::size_t>(dims.x) * dims.y * dims.z; }
};

// The grid of the records' bounding spheres (centerDensity.xyz, toParticle[1].w); one empty cell
// when there are no records. maxEntries ≥ records.size() bounds the listing's length.
ParticleCellGrid buildParticleCellGrid(const std::vector<GpuParticleRecord>& records, std::size_t maxEntries);

}  // namespace cloudlut::render
