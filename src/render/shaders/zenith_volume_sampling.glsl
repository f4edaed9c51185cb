// zenith_volume_sampling.glsl — reading the zenith optical-depth volume in a shader (GLSL only):
// the sun volume's structure (sun_volume.glsl, render/SunVolume) built a second time with its
// columns vertical (toward world +y), so that a node holds the optical depth of the cloud above it
// and slice 0 the whole column. Bind it with SunVolume::bind(uniforms, unit, "uZenith"). Requires
// SUN_CASCADES_MAX. With uZenithCascades = 0 (no volume built) no cloud lies above or below.

uniform sampler3D uZenithTau;    // R32F, cascades stacked along the depth; S, T clamp to border 0
uniform int uZenithCascades;
uniform ivec3 uZenithDims;       // columns Nu, Nv and slices Nw of one cascade
uniform mat4 uZenithToGrid[SUN_CASCADES_MAX];

// Vertical optical depths (dimensionless) of the cloud at world point x, from the finest cascade
// whose columns hold x (trilinear): x = above it (toward +y, out of the grid), y = below it (the
// whole column less the part above). (0, 0) outside every cascade.
vec2 zenithOpticalDepths(vec3 x) {
  for (int k = 0; k < uZenithCascades; ++k) {
    vec3 g = (uZenithToGrid[k] * vec4(x, 1.0)).xyz;
    vec2 inner = vec2(uZenithDims.xy) - 1.0;
    if (g.x < 0.0 || g.y < 0.0 || g.x > inner.x || g.y > inner.y) continue;
    float w = clamp(g.z, 0.0, float(uZenithDims.z) - 1.0);
    vec2 xy = (g.xy + 0.5) / vec2(uZenithDims.xy);
    float depth = float(uZenithDims.z * uZenithCascades);
    float above = texture(uZenithTau, vec3(xy, (float(k * uZenithDims.z) + w + 0.5) / depth)).r;
    float column = texture(uZenithTau, vec3(xy, (float(k * uZenithDims.z) + 0.5) / depth)).r;
    return vec2(above, max(column - above, 0.0));
  }
  return vec2(0.0);
}
