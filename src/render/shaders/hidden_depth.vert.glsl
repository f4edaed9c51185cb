// hidden_depth.vert.glsl — one triangle that covers the viewport (vertices 0, 1, 2).
void main() {
  vec2 corner = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));
  gl_Position = vec4(corner, 0.0, 1.0);
}
