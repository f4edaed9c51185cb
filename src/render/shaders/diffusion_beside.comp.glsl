// diffusion_beside.comp.glsl — the weight of the cloud beside each node of the diffusion volume
// (render/DiffusionVolume.h, docs/LIGHTING.md "The cloud beside a particle"), for the particle
// shader's share of the diffused light (diffusion_sampling.glsl). Preceded by the files of
// sun_volume_sampling.glsl (sunOpticalDepth, localCloudAlongSun, localColumnsBeside) and
// cloudlut_shading.glsl (cloudBesideWeight). One invocation per node of the level uBesideStride
// times coarser than the finest (node I at fine node uBesideStride·I): cloudBesideWeight of the
// local cloud columns uBesideOffset away across the sun against the node's own (dimensionless).

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

uniform ivec3 uNodes;          // nodes per grid axis of this level
uniform mat4 uNodeToWorld;     // fine node (i, j, k) → world point
uniform float uBesideOffset;   // how far beside (world units)
uniform float uBesideStride;   // fine nodes per node (1 or 2)

layout(r32f, binding = 4) uniform writeonly image3D uBeside;

void main() {
  ivec3 n = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(n, uNodes))) return;
  vec3 x = (uNodeToWorld * vec4(uBesideStride * vec3(n), 1.0)).xyz;
  float column = localCloudAlongSun(x, sunOpticalDepth(x)).y;
  imageStore(uBeside, n, vec4(cloudBesideWeight(localColumnsBeside(x, uBesideOffset), column), 0.0, 0.0, 0.0));
}
