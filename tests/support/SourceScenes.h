#pragma once
// The scenes of the source tree (data/scenes, data/bench_scenes) as tests read them, and render
// settings that view one from its own camera.
#include <string>

#include "render/RenderTypes.h"
#include "scene/Scene.h"

namespace cloudlut::test {

// The scene file at `relative` below the source tree, e.g. "data/scenes/small.json".
inline scene::Scene sourceScene(const std::string& relative) {
  return scene::readScene(std::string(CLOUDLUT_SOURCE_DIR) + "/" + relative);
}

// Settings that render `s` from the scene's own view (scene::resolveView with no command-line
// overrides) at width × height pixels with `blend`; everything else at its default.
inline render::RenderSettings sceneSettings(const scene::Scene& s, int width, int height,
                                            render::BlendMode blend = render::BlendMode::Alpha) {
  render::RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.view = scene::resolveView(s, {});
  settings.blend = blend;
  return settings;
}

}  // namespace cloudlut::test
