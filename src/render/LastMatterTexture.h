#pragma once
// The optical-depth texture the renderer shades with (RGBA32F, the file's layout: texel
// (i0, i1, i2 + N2·i3)): channel 0 the mean density and channel 1 the first matter, as in the
// file, and channel 2 the last matter of each node's chord (core/LastMatter.h), derived on the
// GPU by one compute pass over the nodes (shaders/last_matter.comp.glsl), so that a shader reads
// a chord's first and last matter in one fetch. Channel 3 is 0.
#include "core/Table4D.h"
#include "render/GlContext.h"
#include "render/GlFunctions.h"

namespace cloudlut::render {

// A new texture (left bound to GL_TEXTURE_3D); UsageError when the table does not fit this
// OpenGL's 3D textures (createFloatTexture3D), GlError when the pass fails.
GLuint createOpticalDepthTexture(const GlFunctions& gl, const GlContext& context, const Table4D& opticalDepth);

}  // namespace cloudlut::render
