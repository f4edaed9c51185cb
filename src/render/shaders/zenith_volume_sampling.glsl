// zenith_volume_sampling.glsl — reading the zenith optical-depth volume in a shader (GLSL only):
// the sun volume's structure (sun_volume.glsl, render/SunVolume) built a second time with its
// columns vertical (toward world +y), so that a node holds the optical depth of the cloud above it
// and slice 0 the whole column. Bind it with SunVolume::bind(uniforms, unit, "uZenith"). Requires
// SUN_CASCADES_MAX and cascade_columns.glsl. With uZenithCascades = 0 (no volume built) no cloud
// lies above or below.

uniform sampler3D uZenithTau;    // R32F, cascades stacked along the depth; S, T clamp to border 0
uniform int uZenithCascades;
uniform ivec3 uZenithDims;       // columns Nu, Nv and slices Nw of one cascade
uniform mat4 uZenithToGrid[SUN_CASCADES_MAX];

// Vertical optical depths (dimensionless) of the cloud at world point x, from the finest cascade
// whose columns hold x (trilinear): x = above it (toward +y, out of the grid), y = below it (the
// whole column less the part above). (0, 0) outside every cascade.
vec2 zenithOpticalDepths(vec3 x) {
  vec3 g;
  int k = finestCascadeHolding(uZenithToGrid, uZenithCascades, uZenithDims, x, g);
  if (k < 0) return vec2(0.0);
  vec2 aboveAndColumn = cascadeSliceAndFarEnd(uZenithTau, uZenithDims, uZenithCascades, k, g);
  return vec2(aboveAndColumn.x, max(aboveAndColumn.y - aboveAndColumn.x, 0.0));
}
