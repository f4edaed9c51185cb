// particle.vert.glsl — rasterises each particle's bounding box (seed §5.4). One instance per
// particle, in the back-to-front order of the particle buffer; 36 vertices per box, wound
// counter-clockwise seen from outside (the renderer culls front faces, so each covered pixel
// gets exactly one fragment per particle, even with the camera inside the box).

uniform mat4 uViewProjection;

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
  GpuParticle p = particles[gl_InstanceID];
  vec3 corner = kBoxCorners[(gl_VertexID / 6) * 4 + kQuadCorner[gl_VertexID % 6]];
  mat3 toWorld = mat3(p.toWorld[0].xyz, p.toWorld[1].xyz, p.toWorld[2].xyz);
  vWorld = p.centerDensity.xyz + toWorld * corner;
  vParticle = gl_InstanceID;
  gl_Position = uViewProjection * vec4(vWorld, 1.0);
}
