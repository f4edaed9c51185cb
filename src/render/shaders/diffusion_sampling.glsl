// diffusion_sampling.glsl — reading the diffusion volume (render/DiffusionVolume.h) in the particle
// shader (GLSL only). Bind it with DiffusionVolume::bind.

uniform sampler3D uDiffusionField;  // RGBA32F per node: φ (fluence per unit sun irradiance), J (world)
uniform int uDiffusionBuilt;        // 0: no field this frame
uniform ivec3 uDiffusionNodes;
uniform mat4 uDiffusionToNode;      // world point → node coordinates (node (i, j, k) at integers)
uniform float uDiffusionFade;       // nodes over which the field fades out inside the horizontal sides (0: none)
uniform sampler3D uDiffusionBeside; // R32F: the weight of the cloud beside (cloudBesideWeight) every
uniform float uDiffusionBesideStride; // uDiffusionBesideStride-th node of the field's (1 or 2)
uniform ivec3 uDiffusionBesideNodes;  // its texels per axis

// φ and J (per unit sun irradiance; J in world axes, per unit area) at world point x, trilinear
// between the nodes; how far the field holds there (`presence`): 0 outside the grid or
// without one, else 1, except in a box over part of a wider scene (uDiffusionFade > 0), where
// it rises from 0 three nodes inside a horizontal side (grid axes 0 and 1; the clear air the grid
// keeps beyond a cloud) to 1 uDiffusionFade nodes further in: there the box cuts clouds, and
// their light leaks out of the cut; and the weight of the cloud beside x across the sun
// (`beside`, cloudBesideWeight, trilinear between its nodes; 0 outside the grid or without one).
vec4 diffusionFieldAt(vec3 x, out float presence, out float beside) {
  vec3 g = (uDiffusionToNode * vec4(x, 1.0)).xyz;
  vec3 last = vec3(uDiffusionNodes) - 1.0;
  presence = 0.0;
  beside = 0.0;
  if (uDiffusionBuilt == 0 || any(lessThan(g, vec3(0.0))) || any(greaterThan(g, last))) return vec4(0.0);
  presence = 1.0;
  if (uDiffusionFade > 0.0) {
    vec2 side = min(g.xy, last.xy - g.xy);
    presence = clamp((min(side.x, side.y) - 3.0) / uDiffusionFade, 0.0, 1.0);
  }
  beside = texture(uDiffusionBeside, (g / uDiffusionBesideStride + 0.5) / vec3(uDiffusionBesideNodes)).x;
  return texture(uDiffusionField, (g + 0.5) / vec3(uDiffusionNodes));
}
