#pragma once
// The render verbs' atmosphere: the tables for a scene whose sky is the atmosphere, taken from
// the LUT set when it holds them for the same parameters (`cloudlut bake --tables atmosphere`),
// baked otherwise (bake/AtmosphereBaker.h, well under a second), and handed to the renderer.
#include "io/LutIo.h"
#include "render/Renderer.h"
#include "scene/Scene.h"

namespace cloudlut::cli {

// Nothing when the lighting's sky is uniform.
void setUpAtmosphere(render::Renderer& renderer, const io::LutSet& luts, const scene::Lighting& lighting);

}  // namespace cloudlut::cli
