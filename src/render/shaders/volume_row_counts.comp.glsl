// volume_row_counts.comp.glsl — sums the particle pass's fragments counted per pixel
// (particle_count.frag.glsl, the red channel of the colour texture) along each row of the
// buffer: one invocation per row, in work groups of 64. Volume-aware blending plans its bands of
// rows from the sums (render/VolumeResolve.h, planBands). Integer sums, exact and the same for
// any thread count.

layout(local_size_x = 64) in;

layout(rgba32f, binding = 1) uniform readonly image2D uCounts;
layout(std430, binding = 5) writeonly buffer RowCounts {
  uint rowCounts[];  // fragments of row y (bottom row first)
};

void main() {
  ivec2 size = imageSize(uCounts);
  int y = int(gl_GlobalInvocationID.x);
  if (y >= size.y) return;
  uint sum = 0u;
  for (int x = 0; x < size.x; ++x) sum += uint(imageLoad(uCounts, ivec2(x, y)).r);
  rowCounts[y] = sum;
}
