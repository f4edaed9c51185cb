// volume_resolve.comp.glsl — volume-aware blending (seed §5.5, eqs. 10–17, generalised to any
// number of overlapping particles). The particle pass stored, per pixel, a linked list of
// segments (entry and exit distance along the ray, optical depth τ, radiance R scattered toward
// the camera, premultiplied). Here each pixel's segments are cut at every entry and exit; inside
// each piece the extinctions of the particles present add and their sources combine weighted by
// extinction (eq. 15: κ-weighted colour, C_i = R_i / (1 − e^{−τ_i}) the particle's colour),
//   T_piece = e^{−Σκ_i d},  C_piece = (Σ κ_i C_i / Σ κ_i) (1 − T_piece),
// and the pieces are composited front to back (eqs. 16–17). Non-overlapping segments reduce to
// alpha blending; the transmittance is exactly e^{−Σ τ_i} in any case.
//
// Preceded by volume_fragments.glsl and the defines of render/VolumeResolve.cpp: MAX_SEGMENTS
// (kMaxSegmentsPerPixel) and GROUP_SIDE (work groups of GROUP_SIDE² pixels).
//
// Capacity: at most MAX_SEGMENTS segments per pixel are composited exactly (the nearest ones);
// farther ones, and fragments that found no room in the node pool (accumulated by the particle
// pass into the colour image with plain alpha blending, unsorted), are composited behind them.

layout(local_size_x = GROUP_SIDE, local_size_y = GROUP_SIDE) in;

layout(r32ui, binding = 0) uniform readonly uimage2D uHeads;
layout(rgba32f, binding = 1) uniform image2D uColor;  // in: overflow (rgb, T); out: the result
uniform ivec2 uOrigin;  // the tile's first pixel (render/VolumeResolve.h: tiles)
uniform ivec2 uEnd;     // one past its last pixel

float seg_a[MAX_SEGMENTS];
float seg_b[MAX_SEGMENTS];
float seg_k[MAX_SEGMENTS];
vec3 seg_kc[MAX_SEGMENTS];
float ev_t[2 * MAX_SEGMENTS];
int ev_i[2 * MAX_SEGMENTS];

// τ / (1 − e^{−τ}), stable at τ → 0.
float opacityRatio(float tau) { return tau < 1e-4f ? 1.0f + 0.5f * tau : tau / (1.0f - exp(-tau)); }
// (1 − e^{−x}) / x, stable at x → 0.
float expRatio(float x) { return x < 1e-4f ? 1.0f - 0.5f * x : (1.0f - exp(-x)) / x; }

void main() {
  ivec2 px = uOrigin + ivec2(gl_GlobalInvocationID.xy);
  if (px.x >= uEnd.x || px.y >= uEnd.y) return;
  vec4 overflow = imageLoad(uColor, px);
  int n = 0;
  vec3 tailC = vec3(0.0f);
  float tailT = 1.0f;
  uint node = imageLoad(uHeads, px).x;
  bool truncated = false;
  for (int guard = 0; node != FRAGMENT_LIST_END && guard < 1000000; ++guard) {
    vec3 span = fragmentSpan(node);
    float a = span.x;
    float b = span.y;
    float tau = span.z;
    vec3 r = fragmentRadiance(node);
    node = fragmentNext(node);
    b = max(b, a + max(1e-6f * abs(a), 1e-9f));
    int slot = n;
    if (n == MAX_SEGMENTS) {
      truncated = true;
      int far = 0;
      for (int k = 1; k < MAX_SEGMENTS; ++k)
        if (seg_a[k] > seg_a[far]) far = k;
      if (a >= seg_a[far]) {  // the new one is the farthest: to the tail
        tailC += tailT * r;
        tailT *= exp(-tau);
        continue;
      }
      // Evict the farthest stored segment to the tail.
      float evictedTau = seg_k[far] * (seg_b[far] - seg_a[far]);
      tailC += tailT * seg_kc[far] * (seg_b[far] - seg_a[far]) / opacityRatio(evictedTau);
      tailT *= exp(-evictedTau);
      slot = far;
    } else {
      ++n;
    }
    float len = b - a;
    seg_a[slot] = a;
    seg_b[slot] = b;
    seg_k[slot] = tau / len;
    seg_kc[slot] = r * (opacityRatio(tau) / len);  // κ·C = (τ/len) · R / (1 − e^{−τ})
  }
  if (truncated) atomicAdd(truncatedPixels, 1u);

  // Events: entry (index +k+1) and exit (−k−1), sorted by distance (insertion sort).
  int m = 0;
  for (int k = 0; k < n; ++k) {
    ev_t[m] = seg_a[k];
    ev_i[m] = k + 1;
    ++m;
    ev_t[m] = seg_b[k];
    ev_i[m] = -(k + 1);
    ++m;
  }
  for (int k = 1; k < m; ++k) {
    float t = ev_t[k];
    int id = ev_i[k];
    int j = k - 1;
    while (j >= 0 && (ev_t[j] > t || (ev_t[j] == t && ev_i[j] < id))) {
      ev_t[j + 1] = ev_t[j];
      ev_i[j + 1] = ev_i[j];
      --j;
    }
    ev_t[j + 1] = t;
    ev_i[j + 1] = id;
  }
  // Sweep front to back.
  vec3 color = vec3(0.0f);
  float transmittance = 1.0f;
  int activeCount = 0;
  float kappa = 0.0f;
  vec3 kc = vec3(0.0f);
  for (int e = 0; e < m; ++e) {
    if (e > 0 && activeCount > 0) {
      float d = ev_t[e] - ev_t[e - 1];
      if (d > 0.0f) {
        float x = max(kappa, 0.0f) * d;
        color += transmittance * max(kc, vec3(0.0f)) * d * expRatio(x);  // (Σκc/κ)(1 − e^{−κd})
        transmittance *= exp(-x);
      }
    }
    int id = ev_i[e];
    if (id > 0) {
      kappa += seg_k[id - 1];
      kc += seg_kc[id - 1];
      ++activeCount;
    } else {
      kappa -= seg_k[-id - 1];
      kc -= seg_kc[-id - 1];
      --activeCount;
      if (activeCount == 0) {
        kappa = 0.0f;
        kc = vec3(0.0f);
      }
    }
  }
  color += transmittance * tailC;
  transmittance *= tailT;
  color += transmittance * overflow.rgb;
  transmittance *= overflow.a;
  imageStore(uColor, px, vec4(color, transmittance));
}
