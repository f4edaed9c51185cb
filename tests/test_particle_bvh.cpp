// The path tracer's particle BVH (reference/ParticleBvh.h): it must never lose a particle the
// exact ellipsoid test accepts, it must cull, and a scene rendered through it must equal the
// brute-force loop over every particle bit for bit.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "support/CliRunner.h"
#include "io/ExrImage.h"
#include "reference/ParticleBvh.h"
#include "reference/ScenePathTracer.h"
#include "reference/SphereMonteCarlo.h"

using namespace cloudlut;
using namespace cloudlut::reference;

namespace {

// n particles in a box of half-size `spread` (world units): random radii 0.3…1, stretched up to
// 2× and sheared, densities 0.5…2. Deterministic (McRng).
std::vector<SceneParticle> randomParticles(int n, double spread, std::uint64_t seed) {
  McRng rng(seed, 0, 7);
  std::vector<SceneParticle> out;
  for (int i = 0; i < n; ++i) {
    const glm::dvec3 c(spread * (2 * rng.next() - 1), 0.5 * spread * (2 * rng.next() - 1), spread * (2 * rng.next() - 1));
    glm::dmat3 m(0.3 + 0.7 * rng.next());  // unit sphere → world: scale, stretch, shear
    m[0][0] *= 1.0 + rng.next();
    m[1][0] = 0.4 * (rng.next() - 0.5);
    m[2][1] = 0.4 * (rng.next() - 0.5);
    out.push_back({c, glm::inverse(m), 0.5 + 1.5 * rng.next()});
  }
  return out;
}

// Independent exact test: does the segment o + t·d, t ∈ [0, tMax], pass through the inside of
// the ellipsoid (|M⁻¹(x − c)| < 1 somewhere)? Minimise |p(t)|² over the segment.
bool segmentEntersEllipsoid(const SceneParticle& p, const glm::dvec3& o, const glm::dvec3& d, double tMax) {
  const glm::dvec3 po = p.toParticle * (o - p.center), pd = p.toParticle * d;
  double t = -glm::dot(po, pd) / glm::dot(pd, pd);
  t = std::clamp(t, 0.0, tMax);
  const glm::dvec3 q = po + t * pd;
  return glm::dot(q, q) < 1.0;
}

}  // namespace

TEST_CASE("particle BVH: every particle a ray segment enters is a candidate, and most others are culled",
          "[reference-scene][bvh]") {
  const std::vector<SceneParticle> particles = randomParticles(400, 12.0, 3);
  const ParticleBvh bvh(particles);
  McRng rng(5, 1, 2);
  std::vector<std::uint32_t> cand;
  long long hits = 0, candidates = 0, rays = 0;
  for (int r = 0; r < 3000; ++r) {
    // Origins inside and outside the cloud; a third of the directions along a world axis
    // (zero components exercise the slab test's parallel case).
    const glm::dvec3 o(30 * (rng.next() - 0.5), 15 * (rng.next() - 0.5), 30 * (rng.next() - 0.5));
    glm::dvec3 d(2 * rng.next() - 1, 2 * rng.next() - 1, 2 * rng.next() - 1);
    if (r % 3 == 0) {
      d = glm::dvec3(0.0);
      d[r % 9 / 3] = rng.next() < 0.5 ? -1.0 : 1.0;
    }
    d = glm::normalize(d);
    const double tMax = r % 2 ? 1e300 : 5.0 * rng.next();
    bvh.candidates(o, d, tMax, cand);
    REQUIRE(std::is_sorted(cand.begin(), cand.end()));
    REQUIRE(std::adjacent_find(cand.begin(), cand.end()) == cand.end());
    for (std::size_t i = 0; i < particles.size(); ++i)
      if (segmentEntersEllipsoid(particles[i], o, d, tMax)) {
        ++hits;
        INFO("ray " << r << " particle " << i);
        REQUIRE(std::binary_search(cand.begin(), cand.end(), static_cast<std::uint32_t>(i)));
      }
    candidates += static_cast<long long>(cand.size());
    ++rays;
  }
  INFO("hits " << hits << ", candidates " << candidates << " over " << rays << " rays of 400 particles");
  CHECK(hits > 1000);
  CHECK(candidates < 3 * hits);                // the boxes are tight
  CHECK(candidates < rays * 400 / 10);         // and the tree culls
}

TEST_CASE("particle BVH: a scene rendered through the BVH equals the brute-force loop bit for bit",
          "[reference-scene][bvh]") {
  const ReferenceParticle model(DensityModel::Noise, 1);
  SceneMedium medium;
  medium.model = &model;
  medium.particles = randomParticles(40, 2.5, 11);
  const auto ray = [](double px, double py, glm::dvec3& o, glm::dvec3& d) {
    o = glm::dvec3(0, 0, 12);
    d = glm::normalize(glm::dvec3((px - 8) / 8.0 * 0.35, (8 - py) / 8.0 * 0.35, -1.0));
  };
  SceneLight light;
  light.sunDirection = glm::normalize(glm::dvec3(0.3, 1, 0.2));
  ScenePtSettings st;
  st.samplesPerPixel = 3;
  st.jitter = true;
  const ScenePtImage fast = renderScene(medium, light, st, 16, 16, ray);
  st.bruteForce = true;
  const ScenePtImage brute = renderScene(medium, light, st, 16, 16, ray);
  int cloudPixels = 0;
  for (std::size_t i = 0; i < fast.pixels.size(); ++i) {
    INFO("pixel " << i);
    REQUIRE(fast.pixels[i].single == brute.pixels[i].single);
    REQUIRE(fast.pixels[i].multiple == brute.pixels[i].multiple);
    REQUIRE(fast.pixels[i].sky == brute.pixels[i].sky);
    REQUIRE(fast.pixels[i].transmittance == brute.pixels[i].transmittance);
    REQUIRE(fast.pixels[i].vertices == brute.pixels[i].vertices);
    cloudPixels += fast.pixels[i].transmittance < 0.99;
  }
  CHECK(cloudPixels > 50);   // the scene is not empty: the comparison means something
}

TEST_CASE("particle BVH: reference scene --brute-force writes the same image on the 1419-particle patch, and "
          "bench rejects an unknown scene",
          "[reference-scene][bvh]") {
  using namespace cloudlut::test;
  TempDir dir;
  const std::string scene = std::string(CLOUDLUT_SOURCE_DIR) + "/data/bench_scenes/cloudscape-patch.json";
  const std::string common = "reference scene --particles '" + scene + "' --width 10 --height 6 --spp 2 --quiet";
  REQUIRE(runCli(common + " --out '" + (dir / "bvh.exr").string() + "'").exitCode == 0);
  REQUIRE(runCli(common + " --brute-force --out '" + (dir / "brute.exr").string() + "'").exitCode == 0);
  const io::ExrImage a = io::readExrImage(dir / "bvh.exr"), b = io::readExrImage(dir / "brute.exr");
  for (const char* c : {"R", "G", "B", "A", "stderr.G"}) CHECK(a.channel(c) == b.channel(c));
  float alpha = 0;
  for (const float v : a.channel("A")) alpha = std::max(alpha, v);
  CHECK(alpha > 0.5f);  // the patch is in view

  const auto bad = runCli("bench --suite ground-truth --scenes one,nope --quiet --out '" + (dir / "b").string() + "'");
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find("'nope'") != std::string::npos);
  CHECK(bad.err.find("cloudscape-patch") != std::string::npos);
}
