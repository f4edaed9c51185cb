// cloudlut_sampling.glsl — sampling a 4D cloudlut table stored in a 3D texture (GLSL 4.50).
//
// Include cloudlut_geometry.glsl before this file: it defines lutTexCoord.
//
// The texture holds the table in its file layout (lut_formats/FORMAT.md): width N0, height N1,
// depth N2·N3 with depth index i2 + N2·i3, i.e. one block of N2 slices per node of axis 3.
// Set GL_LINEAR minification and magnification filters, no mipmaps, and GL_CLAMP_TO_EDGE on
// all three coordinates. The hardware filters axes 0, 1 and 2 (texel centres of one block
// only, so neighbouring blocks never bleed into each other); axis 3 is interpolated here
// between two fetches. Node i of n sits at the axis fraction i / (n - 1), as in Table4D.

// Depth texture coordinate of axis-2 fraction x2 inside the block of axis-3 node i3:
// texel i3·N2 + 0.5 + x2·(N2 - 1), divided by the depth N2·N3.
float cloudlutDepthCoord(float x2, float i3, float n2, float n3) {
  return (i3 * n2 + 0.5 + clamp(x2, 0.0, 1.0) * (n2 - 1.0)) / (n2 * n3);
}

// The table's channels at axis fractions x ∈ [0, 1]⁴ (clamped): quadrilinear interpolation,
// trilinear in hardware and linear across axis 3. dims = (N0, N1, N2, N3).
vec4 cloudlutSample4D(sampler3D lut, vec4 x, vec4 dims) {
  float p3 = clamp(x.w, 0.0, 1.0) * (dims.w - 1.0);
  float i3 = min(floor(p3), max(dims.w - 2.0, 0.0));  // lower node, as Table4D::sample
  float j3 = min(i3 + 1.0, dims.w - 1.0);              // upper node (= i3 when N3 = 1)
  vec2 xy = vec2(lutTexCoord(x.x, dims.x), lutTexCoord(x.y, dims.y));
  vec4 lower = texture(lut, vec3(xy, cloudlutDepthCoord(x.z, i3, dims.z, dims.w)));
  vec4 upper = texture(lut, vec3(xy, cloudlutDepthCoord(x.z, j3, dims.z, dims.w)));
  return mix(lower, upper, p3 - i3);
}

vec4 cloudlutSample4D(sampler3D lut, vec4 x, ivec4 dims) {
  return cloudlutSample4D(lut, x, vec4(dims));
}
