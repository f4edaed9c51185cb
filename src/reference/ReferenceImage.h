#pragma once
// The path-traced ground truth of a particle scene as an EXR image: the particles of the scene,
// each the reference particle of the medium's density model scaled by its density, seen from the
// view's camera (pixel centres, or jittered) under its sun and sky, rendered by
// reference/ScenePathTracer.h. What `cloudlut reference scene` writes and the ground-truth bench
// judges the renderers against.
#include <vector>

#include "core/Medium.h"
#include "core/Progress.h"
#include "io/ExrImage.h"
#include "reference/ScenePathTracer.h"
#include "scene/Scene.h"

namespace cloudlut::reference {

struct ReferenceSceneStats {
  double seconds = 0;       // wall time of the path tracing
  double meanVertices = 0;  // mean path length, scattering vertices
  long long truncatedPaths = 0;  // paths cut at kMaxPathVertices (reference/ScenePathTracer.h)
};

// Channels: R, G, B (linear radiance: sun colour × (single + multiple) + sky colour × ambient),
// A = 1 − transmittance, their standard errors "stderr.R", "stderr.G", "stderr.B", "stderr.A"
// (of each pixel's mean), and the uncoloured components "single", "multiple" (per unit sun
// irradiance, sr⁻¹) and "ambient" (per unit sky radiance above the horizon; below it the sky is
// view.lighting.skyBelow times that, one fraction for every channel). The phase functions are the
// medium's (they override settings.first / later). Attribute "cloudlutReference" records the
// medium and the settings as JSON. `stats` (optional) receives the time and mean path length.
// std::invalid_argument (mediumWorkProblem's message) when a particle is too thick to trace;
// WorkLimitExceeded when settings.maxSeconds passes.
// `detail`: the density's detail noise (core/DetailNoise.h; off by default), the renderer's.
io::ExrImage renderReferenceScene(const std::vector<scene::Particle>& particles, const scene::View& view,
                                  const Medium& medium, const ScenePtSettings& settings, int width, int height,
                                  const ProgressFn& progress = {}, ReferenceSceneStats* stats = nullptr,
                                  const DetailNoise& detail = {});

}  // namespace cloudlut::reference
