// How: one printf per line of the report, in the order the stages run.
#include "cli/RenderReport.h"

#include <algorithm>
#include <cstdio>

namespace cloudlut::cli {

void printFrameReport(const std::filesystem::path& file, const render::Image& image, const render::RenderStats& stats,
                      const render::RenderSettings& settings, double setupSeconds, const std::string& contextDescription) {
  std::printf("wrote %s: %dx%d, %zu particles, %s blending, generate %.1f ms, occlusion %.1f ms, render %.1f ms "
              "(setup %.1f ms, %s)\n",
              file.c_str(), image.width, image.height, stats.particles, render::toString(settings.blend),
              1e3 * stats.generateSeconds, 1e3 * stats.occlusionSeconds, 1e3 * stats.renderSeconds,
              1e3 * setupSeconds, contextDescription.c_str());
  if (stats.lightSpaceKept)
    std::printf("  light-space volumes kept from the frame before (the same particles, sun and grids)\n");
  else if (stats.lightSpaceSunOnly)
    std::printf("  only the sun moved: its volume rebuilt, the zenith and diffusion column volumes kept%s\n",
                stats.diffusionWarm ? ", the diffusion solve started from the frame before's" : "");
  if (stats.litParticles > 0)
    std::printf("  light-space passes over %zu particles within the far distance (in view or not)\n",
                stats.litParticles);
  if (settings.downscale > 1)
    std::printf("  particles at 1/%d resolution, upscale %.1f ms\n", settings.downscale, 1e3 * stats.upscaleSeconds);
  if (settings.blend == render::BlendMode::Volume)
    std::printf("  volume blending: %zu tile(s) (%s; %zu split for the fragment load), pool %.1f MiB, %zu fragments, "
                "%zu overflowed (alpha-blended), %zu pixels over %d segments, %zu over %d (chunked), %zu over %d "
                "(resolved in more than one chunk), resolve %.1f ms\n",
                stats.volumeTiles, stats.volumeTilesCounted ? "planned from the counted fragments" : "planned from the expected load",
                stats.volumeRedrawnTiles, static_cast<double>(stats.volumePoolBytes) / 1048576.0,
                stats.fragments, stats.fragmentOverflow, stats.midListPixels,
                std::min(render::kSortedResolveSlots[1], settings.volumeShortList), stats.longListPixels, settings.volumeShortList, stats.truncatedPixels, render::kMaxSegmentsPerPixel,
                1e3 * stats.resolveSeconds);
  if (stats.resolveCutPixels > 0)
    std::fprintf(stderr,
                 "cloudlut render: warning: %zu pixels hold more fragments than this GL's loop budget lets the "
                 "volume resolve composite (llvmpipe: 65535 loop passes per shader invocation); their farther "
                 "segments are missing\n",
                 stats.resolveCutPixels);
  if (stats.sunFootprintOverflow > 0)
    std::printf("  sun volume: %zu particle-cascade pair(s) over the footprint limit, left to a coarser cascade\n",
                stats.sunFootprintOverflow);
  if (settings.sunChordMap && stats.sunChordsNeeded > 0 && !stats.sunChordMap)
    std::printf("  sun volume: the chord map (%.1f MiB) is over the GPU buffer budget; the particle shader "
                "computes the chords again\n",
                static_cast<double>(stats.sunChordsNeeded) * 16.0 / 1048576.0);
}

}  // namespace cloudlut::cli
