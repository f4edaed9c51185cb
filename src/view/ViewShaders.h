#pragma once
// The viewer's own GLSL (src/view/shaders, embedded at build time): the frame presentation and
// the overlay text. Each program is <name>.vert.glsl + <name>.frag.glsl after "#version 450 core".
#include <string>

#include "render/GlFunctions.h"
#include "render/GlResources.h"

namespace cloudlut::view {

// Compiles and links the program `name` (e.g. "view_present"); render::GlError with the
// compiler's log otherwise.
render::GlProgram linkViewProgram(const render::GlFunctions& gl, const std::string& name);

}  // namespace cloudlut::view
