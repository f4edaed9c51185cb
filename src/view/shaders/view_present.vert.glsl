// One triangle covering the viewport; uv (0, 0) at the bottom-left corner of the screen.
out vec2 uv;

void main() {
  const vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  uv = corner;
  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
