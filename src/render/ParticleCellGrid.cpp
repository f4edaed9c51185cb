#include "render/ParticleCellGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace cloudlut::render {

namespace {

struct Bound {
  glm::vec3 centre;
  float radius;
};

// The cells a bound's widened box overlaps, per axis [lo, hi].
void cellRange(const Bound& b, const ParticleCellGrid& g, glm::ivec3& lo, glm::ivec3& hi) {
  const glm::vec3 margin = 0.01f * g.cellSize + glm::vec3(b.radius);
  const glm::vec3 a = (b.centre - margin - g.origin) / g.cellSize, z = (b.centre + margin - g.origin) / g.cellSize;
  lo = glm::clamp(glm::ivec3(glm::floor(a)), glm::ivec3(0), g.dims - 1);
  hi = glm::clamp(glm::ivec3(glm::floor(z)), glm::ivec3(0), g.dims - 1);
}

std::size_t entriesFor(const std::vector<Bound>& bounds, const ParticleCellGrid& g) {
  std::size_t n = 0;
  for (const Bound& b : bounds) {
    glm::ivec3 lo, hi;
    cellRange(b, g, lo, hi);
    const glm::ivec3 span = hi - lo + 1;
    n += static_cast<std::size_t>(span.x) * span.y * span.z;
  }
  return n;
}

}  // namespace

ParticleCellGrid buildParticleCellGrid(const std::vector<GpuParticleRecord>& records, std::size_t maxEntries) {
  ParticleCellGrid g;
  if (records.empty()) {
    g.cellStart.assign(2, 0);
    return g;
  }
  std::vector<Bound> bounds(records.size());
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (std::size_t i = 0; i < records.size(); ++i) {
    const GpuParticleRecord& r = records[i];
    bounds[i] = {glm::vec3(r.centerDensity[0], r.centerDensity[1], r.centerDensity[2]), r.toParticle[1][3]};
    lo = glm::min(lo, bounds[i].centre - bounds[i].radius);
    hi = glm::max(hi, bounds[i].centre + bounds[i].radius);
  }
  // Cells about one median bounding diameter wide, at most kMaxCellsPerAxis per axis.
  std::vector<float> radii(bounds.size());
  std::transform(bounds.begin(), bounds.end(), radii.begin(), [](const Bound& b) { return b.radius; });
  std::nth_element(radii.begin(), radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2), radii.end());
  const float median = radii[radii.size() / 2];
  const glm::vec3 extent = glm::max(hi - lo, glm::vec3(1e-6f * std::max(1.0f, glm::length(hi))));
  glm::ivec3 dims(1);
  for (int a = 0; a < 3 && records.size() > kCellGridMinParticles; ++a)
    dims[a] = static_cast<int>(std::clamp(std::ceil(extent[a] / std::max(2.0f * median, 1e-30f)), 1.0f,
                                          static_cast<float>(kMaxCellsPerAxis)));
  g.origin = lo;
  for (;;) {
    g.dims = dims;
    g.cellSize = extent / glm::vec3(dims);
    if (entriesFor(bounds, g) <= maxEntries || dims == glm::ivec3(1)) break;
    dims = glm::max(dims / 2, glm::ivec3(1));
  }

  // Count, prefix-sum, fill (each cell's indices ascending: records are visited in order).
  g.cellStart.assign(g.cells() + 1, 0);
  const auto forEachCell = [&](const Bound& b, auto&& visit) {
    glm::ivec3 a, z;
    cellRange(b, g, a, z);
    for (int k = a.z; k <= z.z; ++k)
      for (int j = a.y; j <= z.y; ++j)
        for (int i = a.x; i <= z.x; ++i) visit((static_cast<std::size_t>(k) * g.dims.y + j) * g.dims.x + i);
  };
  for (const Bound& b : bounds) forEachCell(b, [&](std::size_t c) { ++g.cellStart[c + 1]; });
  for (std::size_t c = 0; c < g.cells(); ++c) g.cellStart[c + 1] += g.cellStart[c];
  g.indices.resize(g.cellStart.back());
  std::vector<std::uint32_t> fill(g.cellStart.begin(), g.cellStart.end() - 1);
  for (std::size_t i = 0; i < bounds.size(); ++i)
    forEachCell(bounds[i], [&](std::size_t c) { g.indices[fill[c]++] = static_cast<std::uint32_t>(i); });
  return g;
}

}  // namespace cloudlut::render
