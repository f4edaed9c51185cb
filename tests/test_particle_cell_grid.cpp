// The ray marcher's particle cell grid (render/ParticleCellGrid.h): every cell that a particle's
// bounding sphere reaches lists it, checked against a direct sphere–box distance; the listing
// stays within its budget; small scenes share one cell.
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "render/ParticleCellGrid.h"

using namespace cloudlut::render;

namespace {

GpuParticleRecord bound(glm::vec3 centre, float radius) {
  GpuParticleRecord r{};
  for (int a = 0; a < 3; ++a) r.centerDensity[a] = centre[a];
  r.toParticle[1][3] = radius;
  return r;
}

std::vector<GpuParticleRecord> randomBounds(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-50.0f, 50.0f), rad(0.5f, 6.0f);
  std::vector<GpuParticleRecord> records;
  for (std::size_t i = 0; i < n; ++i) records.push_back(bound({pos(rng), 0.2f * pos(rng), pos(rng)}, rad(rng)));
  return records;
}

bool listed(const ParticleCellGrid& g, std::size_t cell, std::uint32_t particle) {
  const auto a = g.indices.begin() + g.cellStart[cell], z = g.indices.begin() + g.cellStart[cell + 1];
  return std::binary_search(a, z, particle);
}

}  // namespace

TEST_CASE("particle cell grid: every cell a bounding sphere reaches lists the particle", "[raymarch]") {
  const std::vector<GpuParticleRecord> records = randomBounds(600, 7);
  const ParticleCellGrid g = buildParticleCellGrid(records, std::size_t{1} << 24);
  REQUIRE(g.cellStart.size() == g.cells() + 1);
  CHECK(g.dims.x > 4);
  CHECK(g.dims.z > 4);
  CHECK(g.indices.size() == g.cellStart.back());
  std::size_t reached = 0;
  for (int z = 0; z < g.dims.z; ++z)
    for (int y = 0; y < g.dims.y; ++y)
      for (int x = 0; x < g.dims.x; ++x) {
        const std::size_t cell = (static_cast<std::size_t>(z) * g.dims.y + y) * g.dims.x + x;
        REQUIRE(std::is_sorted(g.indices.begin() + g.cellStart[cell], g.indices.begin() + g.cellStart[cell + 1]));
        const glm::vec3 lo = g.origin + glm::vec3(x, y, z) * g.cellSize, hi = lo + g.cellSize;
        for (std::uint32_t i = 0; i < records.size(); ++i) {
          const glm::vec3 c(records[i].centerDensity[0], records[i].centerDensity[1], records[i].centerDensity[2]);
          const float gap = glm::length(c - glm::clamp(c, lo, hi));  // sphere centre to box
          if (gap >= records[i].toParticle[1][3]) continue;
          ++reached;
          INFO("particle " << i << ", cell " << x << "," << y << "," << z);
          CHECK(listed(g, cell, i));
        }
      }
  CHECK(reached >= records.size());
  CHECK(g.indices.size() >= reached);
  CHECK(g.indices.size() <= 8 * reached);  // the boxes list a few more cells than the spheres reach
}

TEST_CASE("particle cell grid: coarsened to its budget; small scenes share one cell", "[raymarch]") {
  const std::vector<GpuParticleRecord> records = randomBounds(600, 8);
  const ParticleCellGrid fine = buildParticleCellGrid(records, std::size_t{1} << 24);
  const ParticleCellGrid coarse = buildParticleCellGrid(records, fine.indices.size() / 3);
  CHECK(coarse.indices.size() <= fine.indices.size() / 3);
  CHECK(coarse.cells() < fine.cells());
  const ParticleCellGrid single = buildParticleCellGrid(records, records.size());  // only one cell fits
  CHECK(single.cells() == 1);
  CHECK(single.indices.size() == records.size());

  const std::vector<GpuParticleRecord> few(records.begin(), records.begin() + kCellGridMinParticles);
  const ParticleCellGrid small = buildParticleCellGrid(few, std::size_t{1} << 24);
  CHECK(small.cells() == 1);
  CHECK(small.indices.size() == few.size());
  const ParticleCellGrid none = buildParticleCellGrid({}, 16);
  CHECK(none.cells() == 1);
  CHECK(none.cellStart == std::vector<std::uint32_t>{0, 0});
}
