// particle.vert.glsl — rasterises each particle's bounding box (seed §5.4). One instance per
// particle, in the back-to-front order of the particle buffer or of the sorted keys; 36 vertices per box, wound
// counter-clockwise seen from outside (the renderer culls front faces, so each covered pixel
// gets exactly one fragment per particle, even with the camera inside the box).

uniform mat4 uViewProjection;
uniform int uUseOrder;  // 1: draw in the order of the sorted keys (GPU bitonic sort), 0: buffer order

layout(std430, binding = 1) readonly buffer SortKeys {
  uvec2 sortKeys[];  // (distance bits, particle index), back to front
};

out vec3 vWorld;
flat out int vParticle;

const vec3 kBoxCorners[24] = vec3[24](
  vec3( 1, -1, -1), vec3( 1,  1, -1), vec3( 1,  1,  1), vec3( 1, -1,  1),   // +x
  vec3(-1, -1, -1), vec3(-1, -1,  1), vec3(-1,  1,  1), vec3(-1,  1, -1),   // -x
  vec3(-1,  1, -1), vec3(-1,  1,  1), vec3( 1,  1,  1), vec3( 1,  1, -1),   // +y
  vec3(-1, -1, -1), vec3( 1, -1, -1), vec3( 1, -1,  1), vec3(-1, -1,  1),   // -y
  vec3(-1, -1,  1), vec3( 1, -1,  1), vec3( 1,  1,  1), vec3(-1,  1,  1),   // +z
  vec3(-1, -1, -1), vec3(-1,  1, -1), vec3( 1,  1, -1), vec3( 1, -1, -1));  // -z
const int kQuadCorner[6] = int[6](0, 1, 2, 0, 2, 3);

void main() {
  int index = uUseOrder != 0 ? int(sortKeys[gl_InstanceID].y) : gl_InstanceID;
  GpuParticle p = particles[index];
  vec3 corner = kBoxCorners[(gl_VertexID / 6) * 4 + kQuadCorner[gl_VertexID % 6]];
  mat3 toWorld = mat3(p.toWorld[0].xyz, p.toWorld[1].xyz, p.toWorld[2].xyz);
  vWorld = p.centerDensity.xyz + toWorld * corner;
  vParticle = index;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
