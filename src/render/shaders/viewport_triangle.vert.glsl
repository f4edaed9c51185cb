// viewport_triangle.vert.glsl — one triangle that covers the viewport, drawn with
// glDrawArrays(GL_TRIANGLES, 0, 3) and no vertex buffers. Vertex IDs 0, 1, 2 map to
// clip-space (−1, −1), (3, −1), (−1, 3); the rasteriser clips it to the full screen.
// Used by the ray marcher and by the hidden-fragment depth fill.
void main() {
  vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
