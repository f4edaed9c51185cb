// cascade_columns.glsl — reading one cascade of a column volume (GLSL only): the sun volume and
// the zenith volume (render/SunVolume) both stack their cascades along the texture's depth, each
// cascade dims.z slices of dims.x × dims.y columns, slice 0 at the columns' far end.

// True when grid point g (dimensionless texel coordinates of one cascade) lies among the
// cascade's columns, where a trilinear read stays inside them.
bool cascadeHoldsColumns(vec3 g, ivec3 dims) {
  vec2 inner = vec2(dims.xy) - 1.0;
  return g.x >= 0.0 && g.y >= 0.0 && g.x <= inner.x && g.y <= inner.y;
}

// The finest cascade k < cascades whose columns hold world point x (toGrid[k]: world to cascade
// k's grid), and x's grid point in it (g); −1 (g unset) when none does. Only the cheap test runs
// per cascade: llvmpipe runs a loop's body for a whole SIMD batch of invocations as long as one of
// them is still looking, so what is read in the cascade runs once, after this, not once for each
// cascade the batch's invocations fall in. Requires SUN_CASCADES_MAX.
int finestCascadeHolding(mat4 toGrid[SUN_CASCADES_MAX], int cascades, ivec3 dims, vec3 x, out vec3 g) {
  for (int k = 0; k < cascades; ++k) {
    g = (toGrid[k] * vec4(x, 1.0)).xyz;
    if (cascadeHoldsColumns(g, dims)) return k;
  }
  return -1;
}

// The volume's values (its unit, e.g. optical depth) in the column through grid point g of
// cascade k of `cascades`, both trilinear: x at g's slice (clamped to the cascade), y at slice 0.
vec2 cascadeSliceAndFarEnd(sampler3D volume, ivec3 dims, int cascades, int k, vec3 g) {
  float w = clamp(g.z, 0.0, float(dims.z) - 1.0);
  vec2 xy = (g.xy + 0.5) / vec2(dims.xy);
  float depth = float(dims.z * cascades), first = float(k * dims.z);
  return vec2(texture(volume, vec3(xy, (first + w + 0.5) / depth)).r,
              texture(volume, vec3(xy, (first + 0.5) / depth)).r);
}
