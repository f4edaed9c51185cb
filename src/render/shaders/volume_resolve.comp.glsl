// volume_resolve.comp.glsl — volume-aware blending (seed §5.5, eqs. 10–17, generalised to any
// number of overlapping particles) of the pixels with long lists. The particle pass stored, per
// pixel, a linked list of segments (entry and exit distance along the ray, optical depth τ,
// radiance R scattered toward the camera, premultiplied). Here each pixel's segments are cut at
// every entry and exit; inside each piece the extinctions of the particles present add and their
// sources combine weighted by extinction (eq. 15: κ-weighted colour, C_i = R_i / (1 − e^{−τ_i})
// the particle's colour),
//   T_piece = e^{−Σκ_i d},  C_piece = (Σ κ_i C_i / Σ κ_i) (1 − T_piece),
// and the pieces are composited front to back (eqs. 16–17; volume_pieces.glsl). Non-overlapping
// segments reduce to alpha blending; the transmittance is exactly e^{−Σ τ_i} in any case.
//
// One invocation per pixel that volume_resolve_sorted.comp.glsl left in PixelLists' last region
// (more than RenderSettings::volumeShortList segments), in work groups of 64. The arrays below are the
// invocation's own: a GL that keeps them in memory (llvmpipe) pays for them in every invocation
// of a program that declares them, used or not, which is why the short lists are resolved by
// another program.
//
// Preceded by volume_fragments.glsl, volume_pieces.glsl, loop_budget.glsl and the defines of
// render/VolumeResolve.cpp: MAX_SEGMENTS (kMaxSegmentsPerPixel), OPAQUE_TRANSMITTANCE (kOpaqueTransmittance).
//
// Order: the segments are taken in chunks of at most MAX_SEGMENTS, nearest first, in the total
// order of compareKeys (entry distance, then the node's other words): the first chunk is the
// MAX_SEGMENTS nearest, each further pass over the list takes the next MAX_SEGMENTS after the
// last key taken. Each chunk is composited exactly as above, the chunks front to back (overlap
// between chunks is treated as one behind the other), then the fragments that found no room in
// the node pool (accumulated by the particle pass into the colour image with plain alpha
// blending). The result depends on the set of segments only, not on the order in which the
// particle pass pushed them; a pixel with L segments walks its list ⌈L / MAX_SEGMENTS⌉ times, or
// fewer: once the chunks taken let through less than OPAQUE_TRANSMITTANCE (render/VolumeResolve.h,
// kOpaqueTransmittance), the rest is not taken (it would add at most that share of its radiance).

layout(local_size_x = 64) in;

layout(r32ui, binding = 0) uniform readonly uimage2D uHeads;
layout(rgba32f, binding = 1) uniform image2D uColor;  // in: overflow (rgb, T); out: the result
// Pixels whose loops the GL cut short (loop_budget.glsl; a pixel with L segments makes about
// L²/MAX_SEGMENTS passes).
layout(std430, binding = 3) buffer ResolveCut {
  uint cutPixels;
};

float seg_a[MAX_SEGMENTS];
uint seg_node[MAX_SEGMENTS];
float seg_b[MAX_SEGMENTS];
float seg_k[MAX_SEGMENTS];
vec3 seg_kc[MAX_SEGMENTS];
float ev_t[2 * MAX_SEGMENTS];
int ev_i[2 * MAX_SEGMENTS];

// Fills seg_a / seg_node with the (at most MAX_SEGMENTS) first segments of the list at `head`,
// in key order, that come after the bound: after key (boundA, boundNode), or tying with it
// beyond the first `boundTaken` such ties (those were taken already). Returns the count; `more`
// tells whether segments after them are left.
int selectChunk(uint head, bool bounded, float boundA, uint boundNode, int boundTaken, out bool more) {
  more = false;
  int n = 0;
  int tiesSeen = 0;
  uint node = head;
  for (int guard = 0; node != FRAGMENT_LIST_END && guard < 1000000; ++guard) {
    float a = segmentEntry(node);
    uint self = node;
    node = fragmentNext(node);
    if (bounded) {
      int c = compareKeys(a, self, boundA, boundNode);
      if (c < 0) continue;
      if (c == 0) {
        ++tiesSeen;
        if (tiesSeen <= boundTaken) continue;
      }
    }
    int j = n;
    if (n == MAX_SEGMENTS) {
      more = true;
      if (compareKeys(a, self, seg_a[n - 1], seg_node[n - 1]) >= 0) continue;
      j = n - 1;  // the last one drops out
    } else {
      ++n;
    }
    while (j > 0 && compareKeys(a, self, seg_a[j - 1], seg_node[j - 1]) < 0) {
      seg_a[j] = seg_a[j - 1];
      seg_node[j] = seg_node[j - 1];
      --j;
    }
    seg_a[j] = a;
    seg_node[j] = self;
  }
  return n;
}

// Composites the n selected segments exactly (the header's pieces): their radiance, and in .a
// their transmittance.
vec4 compositeChunk(int n) {
  for (int k = 0; k < n; ++k) segmentTerms(seg_node[k], seg_a[k], seg_b[k], seg_k[k], seg_kc[k]);
  // Events: entry (index +k+1) and exit (−k−1), sorted by distance (insertion sort); k is the
  // rank in key order, so ties fall the same way whatever the list order.
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
      if (d > 0.0f) addPiece(color, transmittance, kappa, kc, d);
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
  return vec4(color, transmittance);
}

void main() {
  const uint region = uint(PIXEL_LIST_REGIONS - 1);
  if (gl_GlobalInvocationID.x >= regionCount[region]) return;
  ivec2 px = unpackPixel(pixels[region * pixelCapacity + gl_GlobalInvocationID.x]);
  vec4 overflow = imageLoad(uColor, px);
  uint head = imageLoad(uHeads, px).x;
  vec3 color = vec3(0.0f);
  float transmittance = 1.0f;
  bool bounded = false;
  float boundA = 0.0f;
  uint boundNode = 0u;
  int boundTaken = 0;
  bool more = true;
  int chunks = 0;
  for (; more && chunks < 1000000 / MAX_SEGMENTS; ++chunks) {
    int n = selectChunk(head, bounded, boundA, boundNode, boundTaken, more);
    if (n == 0) break;
    vec4 piece = compositeChunk(n);
    color += transmittance * piece.rgb;
    transmittance *= piece.a;
    // The new bound: the last key taken, and how many of its ties are taken so far.
    int ties = 1;
    while (ties < n && compareKeys(seg_a[n - 1 - ties], seg_node[n - 1 - ties], seg_a[n - 1], seg_node[n - 1]) == 0)
      ++ties;
    if (bounded && ties == n && compareKeys(seg_a[n - 1], seg_node[n - 1], boundA, boundNode) == 0)
      ties += boundTaken;
    bounded = true;
    boundA = seg_a[n - 1];
    boundNode = seg_node[n - 1];
    boundTaken = ties;
    if (transmittance < OPAQUE_TRANSMITTANCE) break;  // what lies behind no longer shows
  }
  if (loopsWereCut()) atomicAdd(cutPixels, 1u);
  else if (chunks > 1) atomicAdd(truncatedPixels, 1u);
  color += transmittance * overflow.rgb;
  transmittance *= overflow.a;
  imageStore(uColor, px, vec4(color, transmittance));
}
