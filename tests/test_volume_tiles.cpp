// Volume-aware blending in screen tiles (render/VolumeResolve.h): the tiling rule, a 1080p
// render within the GL's storage block limit, and tiled against untiled images of a scene whose
// particles overlap several deep.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "render/GlContext.h"
#include "render/Renderer.h"
#include "render/VolumeResolve.h"
#include "scene/Scene.h"
#include "support/CliRunner.h"
#include "support/RenderFixture.h"
#include "support/RenderLuts.h"
#include "support/SourceScenes.h"

using namespace cloudlut;
using namespace cloudlut::render;
using namespace cloudlut::scene;
using namespace cloudlut::test;

namespace {

// The node-pool bytes of an untiled w × h buffer: four counters and 28 bytes per node.
double untiledPoolBytes(int w, int h, int fragmentsPerPixel) { return 16.0 + 28.0 * w * h * fragmentsPerPixel; }

}  // namespace

TEST_CASE("volume tiles: every tile's pool fits the budget and the tiles cover the buffer once", "[render][volume]") {
  struct Case {
    int w, h, fpp;
    double budget;
  };
  for (const Case c : {Case{1280, 720, 16, 128.0 * 1048576.0}, Case{960, 540, 16, 128.0 * 1048576.0},
                       Case{1920, 1080, 64, 8.0 * 1048576.0}, Case{100, 7, 3, 16.0 + 28.0 * 3 * 45},
                       Case{64, 48, 16, 1e9}}) {
    INFO(c.w << "x" << c.h << " fpp " << c.fpp << " budget " << c.budget);
    const VolumeTiling t = planVolumeTiles(c.w, c.h, c.fpp, c.budget);
    CHECK(static_cast<double>(t.poolBytes) <= c.budget);
    CHECK(static_cast<double>(t.poolBytes) == untiledPoolBytes(t.tileWidth, t.tileHeight, c.fpp));
    // Coverage: the tiles reach the far edges and the last ones are not empty.
    CHECK(t.columns * t.tileWidth >= c.w);
    CHECK((t.columns - 1) * t.tileWidth < c.w);
    CHECK(t.rows * t.tileHeight >= c.h);
    CHECK((t.rows - 1) * t.tileHeight < c.h);
    // No more tiles than the budget forces (at most one more than the pixel count over the tile).
    const double perTile = std::floor((c.budget - 16.0) / (28.0 * c.fpp));
    CHECK(t.count() <= std::max(1.0, std::ceil(double(c.w) * c.h / perTile)) * 2.0);
    if (untiledPoolBytes(c.w, c.h, c.fpp) <= c.budget) CHECK(t.count() == 1);
  }
  // The seed's Table 1 buffer (960×540 at 16 fragments) needs 221 MiB: two tiles of 128 MiB.
  CHECK(planVolumeTiles(960, 540, 16, 128.0 * 1048576.0).count() == 2);
  CHECK_THROWS(planVolumeTiles(64, 64, 1024, 1000.0));
}

TEST_CASE("volume tiles: bands planned from counted rows are valid and as few as any partition allows",
          "[render][volume]") {
  // The fewest runs of rows that keep each run within the capacity and the row limit, by
  // dynamic programming over every cut (independent of the greedy plan); a row over the
  // capacity on its own counts as a run.
  auto fewestRuns = [](const std::vector<double>& rows, double capacity, int maxRows) {
    const int n = static_cast<int>(rows.size());
    std::vector<int> best(static_cast<std::size_t>(n) + 1, 1 << 30);
    best[0] = 0;
    for (int end = 1; end <= n; ++end) {
      double load = 0;
      for (int first = end - 1; first >= 0 && end - first <= maxRows; --first) {
        load += rows[static_cast<std::size_t>(first)];
        if (load > capacity && end - first > 1) break;
        best[static_cast<std::size_t>(end)] =
            std::min(best[static_cast<std::size_t>(end)], best[static_cast<std::size_t>(first)] + 1);
      }
    }
    return best[static_cast<std::size_t>(n)];
  };
  unsigned state = 12345u;
  auto next = [&state] { return (state = state * 1664525u + 1013904223u) >> 8; };
  for (int trial = 0; trial < 200; ++trial) {
    const int width = 1 + static_cast<int>(next() % 50), height = 1 + static_cast<int>(next() % 60);
    std::vector<double> rows(static_cast<std::size_t>(height));
    for (double& r : rows) r = (next() % 4 == 0) ? 0.0 : static_cast<double>(next() % 400);  // empty rows too
    const double capacity = 50.0 + static_cast<double>(next() % 900);
    const std::size_t maxPixels = static_cast<std::size_t>(width) * (1 + next() % 20);
    INFO("trial " << trial << ": " << width << "x" << height << ", capacity " << capacity << ", max pixels " << maxPixels);
    const std::vector<VolumeBand> bands = planVolumeBands(rows, width, capacity, maxPixels);
    int expectFirst = 0;
    for (const VolumeBand& b : bands) {
      REQUIRE(b.first == expectFirst);  // contiguous, in order, none empty
      REQUIRE(b.end > b.first);
      expectFirst = b.end;
      double load = 0;
      for (int y = b.first; y < b.end; ++y) load += rows[static_cast<std::size_t>(y)];
      if (b.end - b.first > 1) {
        CHECK(load <= capacity);
        CHECK(static_cast<std::size_t>(width) * static_cast<std::size_t>(b.end - b.first) <= maxPixels);
      }
    }
    CHECK(expectFirst == height);  // every row once
    CHECK(static_cast<int>(bands.size()) ==
          fewestRuns(rows, capacity, static_cast<int>(maxPixels / static_cast<std::size_t>(width))));
  }
}

TEST_CASE("volume tiles: tiled and untiled renders agree, exact for n-way overlap", "[render][volume]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  const Scene scene = sourceScene("data/scenes/small.json");
  RenderSettings s = sceneSettings(scene, 96, 64, BlendMode::Volume);
  s.view.camera.eye = {0.0f, 1.0f, 5.0f};  // closer: the cluster fills most of the image
  RenderStats whole;
  const Image reference = renderer.render(scene.particles, s, &whole);
  REQUIRE(whole.volumeTiles == 1);
  REQUIRE(whole.fragmentOverflow == 0);
  REQUIRE(whole.fragments > std::size_t(3) * 96 * 64 / 4);  // several particles deep over much of it

  // Bands of 5 rows, then runs of 40 pixels within a row; then a plan for one fragment per
  // pixel (bands of 16 rows), which the fragment load overflows: its tiles are undone and split.
  struct Case {
    int tilePixels, fragmentsPerPixel;
    std::size_t minTiles;
    bool splits;
  };
  const int defaultFragments = s.fragmentsPerPixel;
  s.tilePlan = VolumeTilePlan::Expected;  // the expected load's tiles, and their halving
  for (const Case c : {Case{5 * 96, defaultFragments, 11, false}, Case{40, defaultFragments, 11, false},
                       Case{96 * 16, 1, 5, true}}) {
    INFO("tile of " << c.tilePixels << " pixels, " << c.fragmentsPerPixel << " fragments per pixel");
    s.fragmentsPerPixel = c.fragmentsPerPixel;
    s.volumePoolBytes = 16.0L + 28.0L * s.fragmentsPerPixel * c.tilePixels;
    RenderStats tiled;
    const Image image = renderer.render(scene.particles, s, &tiled);
    CHECK(tiled.volumeTiles >= c.minTiles);
    CHECK((tiled.volumeRedrawnTiles > 0) == c.splits);
    CHECK(tiled.fragments == whole.fragments);
    CHECK(tiled.fragmentOverflow == 0);
    CHECK(tiled.truncatedPixels == whole.truncatedPixels);
    double maxDiff = 0;
    for (std::size_t i = 0; i < image.rgba.size(); ++i)
      maxDiff = std::max(maxDiff, double(std::abs(image.rgba[i] - reference.rgba[i])));
    std::size_t distanceMismatch = 0;
    for (std::size_t i = 0; i < image.distance.size(); ++i)
      if (image.distance[i] != reference.distance[i]) ++distanceMismatch;
    std::printf("[volume tiles] %zu tiles (%zu split) of %d pixels: max |tiled - untiled| %.2e\n", tiled.volumeTiles,
                tiled.volumeRedrawnTiles, c.tilePixels, maxDiff);
    CHECK(maxDiff <= 1e-4);
    CHECK(distanceMismatch == 0);
  }

  // The last plan again, from the fragments counted first: the count is the particle pass's own
  // to the fragment, so no band overflows, and the bands are as few as the pool allows.
  s.tilePlan = VolumeTilePlan::Counted;
  RenderStats counted;
  const Image image = renderer.render(scene.particles, s, &counted);
  const double capacity = std::floor((static_cast<double>(s.volumePoolBytes) - 16.0) / 28.0);
  std::printf("[volume tiles] counted plan: %zu bands (%zu split), %zu fragments counted, %zu stored, pool of %.0f nodes\n",
              counted.volumeTiles, counted.volumeRedrawnTiles, counted.countedFragments, counted.fragments, capacity);
  CHECK(counted.volumeTilesCounted);
  CHECK(counted.countedFragments == whole.fragments);
  CHECK(counted.fragments == whole.fragments);
  CHECK(counted.volumeRedrawnTiles == 0);
  CHECK(counted.fragmentOverflow == 0);
  CHECK(static_cast<double>(counted.volumeTiles) >= std::ceil(static_cast<double>(whole.fragments) / capacity));
  double maxDiff = 0;
  for (std::size_t i = 0; i < image.rgba.size(); ++i)
    maxDiff = std::max(maxDiff, double(std::abs(image.rgba[i] - reference.rgba[i])));
  CHECK(maxDiff <= 1e-4);
  // A pool of 512 nodes planned for one fragment per pixel (bands of 5 rows), which the busy rows
  // overflow. The expected plan never counts: its overflowed tiles are split in halves.
  s.fragmentsPerPixel = 1;
  s.volumePoolBytes = 16.0L + 28.0L * 512;
  s.tilePlan = VolumeTilePlan::Expected;
  RenderStats expected;
  renderer.render(scene.particles, s, &expected);
  CHECK(!expected.volumeTilesCounted);
  CHECK(expected.countedFragments == 0);
  CHECK(expected.volumeRedrawnTiles > 1);
  // Under the automatic plan an explicit scene counts first while the last count found the
  // expected plan too small. A roomy frame (bands of 5 rows, 16 fragments a pixel) stops that:
  s.tilePlan = VolumeTilePlan::Auto;
  s.fragmentsPerPixel = defaultFragments;
  s.volumePoolBytes = 16.0L + 28.0L * defaultFragments * 5 * 96;
  RenderStats roomy, afterRoomy;
  renderer.render(scene.particles, s, &roomy);  // counted (the Renderer's first count) or not
  renderer.render(scene.particles, s, &afterRoomy);
  CHECK(!afterRoomy.volumeTilesCounted);
  CHECK(afterRoomy.volumeRedrawnTiles == 0);
  // then the crowded pool again: the count waits for the first overflow. That one tile is drawn
  // again, the rows from it up are counted and cut into bands, and none of those overflows.
  s.fragmentsPerPixel = 1;
  s.volumePoolBytes = 16.0L + 28.0L * 512;
  RenderStats automatic;
  const Image automaticImage = renderer.render(scene.particles, s, &automatic);
  std::printf("[volume tiles] automatic plan: %zu tiles resolved (%zu split; expected plan %zu, %zu split), %zu of %zu "
              "fragments counted\n",
              automatic.volumeTiles, automatic.volumeRedrawnTiles, expected.volumeTiles, expected.volumeRedrawnTiles,
              automatic.countedFragments, whole.fragments);
  CHECK(automatic.volumeTilesCounted);
  CHECK(automatic.volumeRedrawnTiles == 1);
  CHECK(automatic.countedFragments > 0);
  CHECK(automatic.countedFragments <= whole.fragments);
  CHECK(automatic.fragments == whole.fragments);
  CHECK(automatic.fragmentOverflow == 0);
  CHECK(automatic.volumeTiles < expected.volumeTiles);
  double automaticDiff = 0;
  for (std::size_t i = 0; i < automaticImage.rgba.size(); ++i)
    automaticDiff = std::max(automaticDiff, double(std::abs(automaticImage.rgba[i] - reference.rgba[i])));
  CHECK(automaticDiff <= 1e-4);
  std::size_t automaticDistance = 0;
  for (std::size_t i = 0; i < automaticImage.distance.size(); ++i)
    if (automaticImage.distance[i] != reference.distance[i]) ++automaticDistance;
  CHECK(automaticDistance == 0);
  // the next frame of the same load counts before it draws: nothing is drawn twice
  RenderStats nextFrame;
  const Image nextImage = renderer.render(scene.particles, s, &nextFrame);
  CHECK(nextFrame.volumeTilesCounted);
  CHECK(nextFrame.volumeRedrawnTiles == 0);
  CHECK(nextFrame.countedFragments == whole.fragments);
  CHECK(nextImage.rgba == reference.rgba);
  // a frame whose count finds the expected plan big enough stops the counting: the frame after
  // it keeps the expected plan uncounted
  s.fragmentsPerPixel = defaultFragments;
  s.volumePoolBytes = 16.0L + 28.0L * defaultFragments * 5 * 96;
  RenderStats roomyCounted, roomyAfter;
  renderer.render(scene.particles, s, &roomyCounted);
  renderer.render(scene.particles, s, &roomyAfter);
  CHECK(roomyCounted.volumeTilesCounted);
  CHECK(!roomyAfter.volumeTilesCounted);
  CHECK(roomyAfter.volumeRedrawnTiles == 0);
  // a Renderer's first frame under the automatic plan counts first
  RenderFixture fresh = RenderFixture::synthetic(DensityModel::Noise);
  s.fragmentsPerPixel = 1;
  s.volumePoolBytes = 16.0L + 28.0L * 512;
  RenderStats first;
  const Image firstImage = fresh.renderer.render(scene.particles, s, &first);
  CHECK(first.volumeTilesCounted);
  CHECK(first.volumeRedrawnTiles == 0);
  CHECK(first.countedFragments == whole.fragments);
  CHECK(firstImage.rgba == reference.rgba);

  // A pool of 64 nodes, fewer than the busiest rows hold: those rows are bands of one row that
  // overflow, and run() splits them as any overflowed tile, so the image stays exact.
  s.tilePlan = VolumeTilePlan::Counted;
  s.fragmentsPerPixel = 1;
  s.volumePoolBytes = 16.0L + 28.0L * 64;
  RenderStats crowded;
  const Image crowdedImage = renderer.render(scene.particles, s, &crowded);
  std::printf("[volume tiles] counted plan, pool of 64 nodes: %zu tiles resolved, %zu split\n", crowded.volumeTiles,
              crowded.volumeRedrawnTiles);
  CHECK(crowded.volumeTilesCounted);
  CHECK(crowded.volumeRedrawnTiles > 0);
  CHECK(crowded.fragments == whole.fragments);
  CHECK(crowded.fragmentOverflow == 0);
  double crowdedDiff = 0;
  for (std::size_t i = 0; i < crowdedImage.rgba.size(); ++i)
    crowdedDiff = std::max(crowdedDiff, double(std::abs(crowdedImage.rgba[i] - reference.rgba[i])));
  CHECK(crowdedDiff <= 1e-4);
}

TEST_CASE("volume tiles: a 1920x1080 volume render fits the GL's storage block limit", "[render][volume]") {
  RenderFixture rig = RenderFixture::synthetic(DensityModel::Noise);
  Renderer& renderer = rig.renderer;
  const Scene scene = sourceScene("data/scenes/small.json");
  RenderSettings s = sceneSettings(scene, 1920, 1080, BlendMode::Volume);
  s.downscale = 2;  // the seed's Table 1: particles at half resolution
  s.tilePlan = VolumeTilePlan::Expected;  // the tiles of the expected load, which the limit sizes
  RenderStats stats;
  const Image image = renderer.render(scene.particles, s, &stats);
  REQUIRE(image.width == 1920);
  REQUIRE(image.height == 1080);
  CHECK(image.nonFiniteCount() == 0);
  // Untiled it would need more than llvmpipe's 128 MiB block.
  CHECK(untiledPoolBytes(960, 540, s.fragmentsPerPixel) > 128.0 * 1048576.0);
  CHECK(stats.volumeTiles >= 2);
  CHECK(static_cast<double>(stats.volumePoolBytes) <= 128.0 * 1048576.0);
  CHECK(stats.fragments > 0);
  CHECK(stats.fragmentOverflow == 0);
  std::size_t covered = 0;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4)
    if (image.rgba[i] > 0.05f) ++covered;
  CHECK(covered > std::size_t(1920) * 1080 / 20);
  std::printf("[volume tiles] 1920x1080 / 2: %zu tiles, pool %.1f MiB, %zu fragments\n", stats.volumeTiles,
              double(stats.volumePoolBytes) / 1048576.0, stats.fragments);
}
