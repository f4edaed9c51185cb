// upscale.comp.glsl — edge-preserving (bilateral) upscale of the low-resolution particle image
// (seed §5.4), one thread per output pixel. Preceded by the define GROUP_SIDE of
// render/Upscale.cpp (work groups of GROUP_SIDE² pixels).
//
// Pixel (x, y) of the W × H output, rows counted from the top, maps to the point
//   f = ((x + ½) · w/W − ½, (y + ½) · h/H − ½)
// of the w × h input (pixel centres at integers). Its four neighbours (⌊f⌋ + {0, 1}², clamped to
// the image) are blended with the bilinear weights times a depth similarity to the nearest
// sample n = round(f) (halves away from zero, clamped):
//   s(d, d_n) = 1 / (1 + (|d − d_n| / (0.05 · max(d_n, 1e-6)))²),
//   s = 1 where neither has a distance, 1e-3 where only one has,
// d the distance to the first matter; each weight gets 1e-12 so that the sum never vanishes.
// The output takes the weighted mean of (radiance, transmittance) and the nearest sample's
// distance. A cloud's edge against the sky or against a farther cloud stays sharp.

layout(local_size_x = GROUP_SIDE, local_size_y = GROUP_SIDE) in;

layout(rgba32f, binding = 0) uniform readonly image2D uLowColor;  // radiance, transmittance
layout(r32f, binding = 1) uniform readonly image2D uLowDistance;  // uNoDistance where none
layout(rgba32f, binding = 2) uniform writeonly image2D uColor;
layout(r32f, binding = 3) uniform writeonly image2D uDistance;
uniform ivec2 uLowSize;
uniform ivec2 uSize;
uniform float uNoDistance;

float similarity(float d, float ref) {
  bool di = d >= uNoDistance;
  bool ri = ref >= uNoDistance;
  if (di || ri) return di == ri ? 1.0f : 1e-3f;
  float rel = abs(d - ref) / (0.05f * max(ref, 1e-6f));
  return 1.0f / (1.0f + rel * rel);
}

// Texel of the input at column x, row y counted from the top (GL rows count from the bottom).
ivec2 lowTexel(int x, int y) { return ivec2(x, uLowSize.y - 1 - y); }

int roundHalfAway(float f) { return int(f >= 0.0f ? floor(f + 0.5f) : ceil(f - 0.5f)); }

void main() {
  ivec2 g = ivec2(gl_GlobalInvocationID.xy);
  if (g.x >= uSize.x || g.y >= uSize.y) return;
  int x = g.x;
  int y = uSize.y - 1 - g.y;
  float sx = float(uLowSize.x) / float(uSize.x);
  float sy = float(uLowSize.y) / float(uSize.y);
  float fx = (float(x) + 0.5f) * sx - 0.5f;
  float fy = (float(y) + 0.5f) * sy - 0.5f;
  int nx = clamp(roundHalfAway(fx), 0, uLowSize.x - 1);
  int ny = clamp(roundHalfAway(fy), 0, uLowSize.y - 1);
  float ref = imageLoad(uLowDistance, lowTexel(nx, ny)).x;
  int x0 = int(floor(fx));
  int y0 = int(floor(fy));
  float ax = fx - float(x0);
  float ay = fy - float(y0);
  vec4 acc = vec4(0.0f);
  float wsum = 0.0f;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      ivec2 t = lowTexel(clamp(x0 + i, 0, uLowSize.x - 1), clamp(y0 + j, 0, uLowSize.y - 1));
      float w = (i == 1 ? ax : 1.0f - ax) * (j == 1 ? ay : 1.0f - ay) * similarity(imageLoad(uLowDistance, t).x, ref) +
                1e-12f;
      acc += w * imageLoad(uLowColor, t);
      wsum += w;
    }
  imageStore(uColor, g, acc / wsum);
  imageStore(uDistance, g, vec4(ref, 0.0f, 0.0f, 0.0f));
}
