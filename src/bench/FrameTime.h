#pragma once
// Issue 17's speed goal in the ground-truth suite: the steady-state frame time of the particle
// renderer against the ray marcher on one scene, at 1280×720 (--quick: 640×360). The LUT
// renderer (cloud lighting, volume-aware blending) at full, ½ and ¼ particle resolution; the
// ray marcher at 32 steps. Each is drawn once unmeasured (llvmpipe compiles a program's code at
// its first draw, which a single `render` run pays), then timed as the best of three frames:
// the particle upload, the light-space passes, shading and blending, the upscale; not the
// read-back.
//
// Every LUT frame three times: cold, the light-space volumes (sun, diffusion) built every frame as
// when the clouds move; kept, reused from the frame before (RenderSettings::keepLighting: still
// clouds under a still sun, the same image); and under a sun turning 1° a frame about the
// vertical, the lighting kept (the sun volume built again, the diffusion solve warm-started).
// And with the seed's lighting model (sunlight per particle, LM(ρ), the crease ambient), whose
// one light-space pass, the tile occlusion, runs every frame: what the cloud model costs over it.
//
// Rows (suite "ground-truth", resolution the frame's): method "frame-lut-volume" (cold),
// "frame-lut-volume-kept", "frame-lut-volume-sun" and "frame-lut-volume-seed" with steps = the
// downscale factor, "frame-raymarch" with steps = 32. For the reduced resolutions and the kept
// frames error_mean is the relative RMSE of the frame against the cold full-resolution frame (RGB
// over the pixels where either is cloud: what the upscale costs; 0 for the kept full-resolution
// frame); for the turning sun's, against a cold full-resolution frame under the same sun (what
// the upscale and the warm start cost); for the seed model's reduced resolutions, against its own
// full-resolution frame. The note gives the speed-up over the ray marcher's frame.
#include <string>
#include <vector>

#include "bench/BenchReport.h"
#include "render/RayMarchRenderer.h"
#include "render/Renderer.h"
#include "scene/Scene.h"

namespace cloudlut::bench {

std::vector<BenchRow> frameTimeRows(const std::string& sceneName, const scene::Scene& scene, const scene::View& view,
                                    render::Renderer& lut, render::RayMarchRenderer& marcher,
                                    const render::RayMarchSettings& marchBase, bool quick);

}  // namespace cloudlut::bench
