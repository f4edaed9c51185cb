// hidden_depth.frag.glsl — the depth of each pixel's hidden distance (render/HiddenFragments.h,
// fillDepth): depth = D · uDepthScale, clamped to [0, 1] (1: nothing hidden). Preceded by
// hidden_fragments.glsl.
uniform float uDepthScale;  // 1 / the far plane (world units⁻¹), as particle.vert.glsl's

void main() { gl_FragDepth = clamp(hiddenBeyond(ivec2(gl_FragCoord.xy)) * uDepthScale, 0.0, 1.0); }
