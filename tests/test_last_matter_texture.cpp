// The renderer's optical-depth texture (render/LastMatterTexture.h) against the CPU derivation
// of the last matter (core/LastMatter.h, itself checked against independent references in
// test_optical_depth.cpp): the GPU pass must give every node the CPU's channels.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bake/OpticalDepthBaker.h"
#include "core/LastMatter.h"
#include "core/ReferenceParticle.h"
#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/LastMatterTexture.h"

using namespace cloudlut;

TEST_CASE("last matter texture: the GPU pass gives every node the CPU's channels", "[render][optical-depth]") {
  bake::OpticalDepthSettings s;
  s.dims = {32, 16, 32, 16};
  const Table4D od = bake::bakeOpticalDepth(ReferenceParticle(DensityModel::Noise, 1), s);
  const Table4D cpu = withLastMatterChannel(od);

  const auto context = render::createHeadlessContext();
  const render::GlFunctions gl = render::makeCurrentAndLoadGlFunctions(*context);
  const GLuint texture = render::createOpticalDepthTexture(gl, *context, od);
  std::vector<float> gpu(od.nodeCount() * 4);
  gl.BindTexture(GL_TEXTURE_3D, texture);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 4);
  gl.GetTexImage(GL_TEXTURE_3D, 0, GL_RGBA, GL_FLOAT, gpu.data());
  gl.DeleteTextures(1, &texture);
  render::checkGlError(gl, "reading the optical-depth texture back");

  // Channels 0 and 1 are the file's, exactly; channel 2 differs by the GPU's trigonometry and
  // interpolation weights, which move the reversed chord's sample by a hair: where the first
  // matter jumps (a thin wisp appears along the chord) a node can land on either side.
  std::vector<double> diff;
  for (std::size_t n = 0; n < od.nodeCount(); ++n) {
    REQUIRE(gpu[4 * n] == cpu.at(n, 0));
    REQUIRE(gpu[4 * n + 1] == cpu.at(n, 1));
    diff.push_back(std::abs(gpu[4 * n + 2] - cpu.at(n, 2)));
  }
  std::sort(diff.begin(), diff.end());
  const double p999 = diff[diff.size() * 999 / 1000], worst = diff.back();
  std::printf("last matter texture: %zu nodes, |GPU - CPU| median %.2e, p99.9 %.2e, max %.2e\n", diff.size(),
              diff[diff.size() / 2], p999, worst);
  CHECK(diff[diff.size() / 2] < 1e-5);
  CHECK(p999 < 1e-3);
}
