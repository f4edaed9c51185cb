// diffusion_sampling.glsl — reading the diffusion volume (render/DiffusionVolume.h) in the particle
// shader (GLSL only). Bind it with DiffusionVolume::bind.

uniform sampler3D uDiffusionField;  // RGBA32F per node: φ (fluence per unit sun irradiance), J (world)
uniform int uDiffusionBuilt;        // 0: no field this frame
uniform ivec3 uDiffusionNodes;
uniform mat4 uDiffusionToNode;      // world point → node coordinates (node (i, j, k) at integers)

// φ and J (per unit sun irradiance; J in world axes, per unit area) at world point x, trilinear
// between the nodes; w < 0 (no field) outside the grid or without one.
vec4 diffusionFieldAt(vec3 x, out bool inside) {
  vec3 g = (uDiffusionToNode * vec4(x, 1.0)).xyz;
  vec3 last = vec3(uDiffusionNodes) - 1.0;
  inside = uDiffusionBuilt != 0 && all(greaterThanEqual(g, vec3(0.0))) && all(lessThanEqual(g, last));
  if (!inside) return vec4(0.0);
  return texture(uDiffusionField, (g + 0.5) / vec3(uDiffusionNodes));
}
