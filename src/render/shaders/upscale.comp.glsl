// upscale.comp.glsl — edge-preserving (bilateral) upscale of the low-resolution particle image
// (seed §5.4), one thread per output pixel. Preceded by the define GROUP_SIZE of
// render/Upscale.cpp (work groups of GROUP_SIZE pixels along a row), which dispatches one band of
// output rows at a time (uFirstRow on: the bound buffer ranges hold that band).
//
// Pixel (x, y) of the W × H output, rows counted from the top, maps to the point
//   f = ((x + ½) · w/W − ½, (y + ½) · h/H − ½)
// of the w × h input (pixel centres at integers). Its four neighbours ⌊f⌋ + {0, 1}², clamped to
// the image, are blended with the bilinear weights times a depth similarity to the nearest
// sample n = round(f) (halves away from zero, clamped; it is the neighbour on the side where the
// fraction f − ⌊f⌋ is at least ½):
//   s(d, d_n) = 1 / (1 + (|d − d_n| / (0.05 · max(d_n, 1e-6)))²),
//   s = 1 where neither has a distance, 1e-3 where only one has,
// d the distance to the first matter; each weight gets 1e-12 so that the sum never vanishes.
// The output takes the weighted mean of (radiance, 1 − transmittance) and the nearest sample's
// distance (+∞ where there is none), in the layout of render::Image. A cloud's edge against the
// sky or against a farther cloud stays sharp.

layout(local_size_x = GROUP_SIZE) in;

layout(rgba32f, binding = 0) uniform readonly image2D uLowColor;  // radiance, transmittance
layout(r32f, binding = 1) uniform readonly image2D uLowDistance;  // uNoDistance where none
layout(std430, binding = 7) writeonly buffer UpscaledColor {
  vec4 outColor[];  // radiance, alpha = 1 − transmittance; rows from the top
};
layout(std430, binding = 8) writeonly buffer UpscaledDistance {
  float outDistance[];
};
uniform ivec2 uLowSize;
uniform ivec2 uSize;
uniform int uFirstRow;
uniform float uNoDistance;

float similarity(float d, float ref) {
  bool di = d >= uNoDistance;
  bool ri = ref >= uNoDistance;
  if (di || ri) return di == ri ? 1.0f : 1e-3f;
  float rel = abs(d - ref) / (0.05f * max(ref, 1e-6f));
  return 1.0f / (1.0f + rel * rel);
}

// Alpha of an input texel (the input holds transmittance).
vec4 lowColor(ivec2 texel) {
  vec4 c = imageLoad(uLowColor, texel);
  return vec4(c.rgb, 1.0f - c.a);
}

void main() {
  int x = int(gl_GlobalInvocationID.x);
  int y = uFirstRow + int(gl_GlobalInvocationID.y);
  if (x >= uSize.x || y >= uSize.y) return;
  float sx = float(uLowSize.x) / float(uSize.x);
  float sy = float(uLowSize.y) / float(uSize.y);
  float fx = (float(x) + 0.5f) * sx - 0.5f;
  float fy = (float(y) + 0.5f) * sy - 0.5f;
  int x0 = int(floor(fx));
  int y0 = int(floor(fy));
  float ax = fx - float(x0);
  float ay = fy - float(y0);
  // The neighbours (columns lo.x, hi.x; rows lo.y, hi.y from the top) as GL texels, whose rows
  // count from the bottom.
  ivec2 lo = clamp(ivec2(x0, y0), ivec2(0), uLowSize - 1);
  ivec2 hi = clamp(ivec2(x0 + 1, y0 + 1), ivec2(0), uLowSize - 1);
  ivec2 t00 = ivec2(lo.x, uLowSize.y - 1 - lo.y);
  ivec2 t10 = ivec2(hi.x, t00.y);
  ivec2 t01 = ivec2(lo.x, uLowSize.y - 1 - hi.y);
  ivec2 t11 = ivec2(hi.x, t01.y);
  float d00 = imageLoad(uLowDistance, t00).x;
  float d10 = imageLoad(uLowDistance, t10).x;
  float d01 = imageLoad(uLowDistance, t01).x;
  float d11 = imageLoad(uLowDistance, t11).x;
  bool right = ax >= 0.5f;
  bool below = ay >= 0.5f;
  float ref = below ? (right ? d11 : d01) : (right ? d10 : d00);
  float w00 = (1.0f - ax) * (1.0f - ay) * similarity(d00, ref) + 1e-12f;
  float w10 = ax * (1.0f - ay) * similarity(d10, ref) + 1e-12f;
  float w01 = (1.0f - ax) * ay * similarity(d01, ref) + 1e-12f;
  float w11 = ax * ay * similarity(d11, ref) + 1e-12f;
  vec4 acc = w00 * lowColor(t00) + w10 * lowColor(t10) + w01 * lowColor(t01) + w11 * lowColor(t11);
  int i = (y - uFirstRow) * uSize.x + x;
  outColor[i] = acc / (w00 + w10 + w01 + w11);
  outDistance[i] = ref >= uNoDistance ? uintBitsToFloat(0x7f800000u) : ref;
}
