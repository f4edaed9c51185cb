// volume_resolve_sorted.comp.glsl — volume-aware blending (seed §5.5, eqs. 15–17) of the pixels
// whose lists hold at most SLOTS segments (4, 8, 16 or 32; a build of this program each): most
// pixels of a frame. The same pieces as volume_resolve.comp.glsl (volume_pieces.glsl): the segments are cut
// at every entry and exit, the extinctions and extinction-weighted sources of the segments present
// in a piece add, the pieces are composited front to back, then the fragments that found no room
// in the pool (overflow, alpha-blended by the particle pass).
//
// Without arrays in memory (a GL that keeps dynamically indexed arrays in memory, llvmpipe, pays
// for them in every invocation): every index below is a constant. The list's first SLOTS
// segments become 2·SLOTS events in fixed slots (entries first, then exits; an empty slot is an
// event at +∞ that changes nothing), a fixed sorting network puts them in order (Batcher's
// odd–even merge sort: 19 compare-exchanges for 8 events, 63 for 16, 191 for 32, 543 for 64), and
// one unrolled sweep keeps the running sums of κ and κ·C as the events pass. Each event carries its own change of
// the sums (an exit's with the sign turned), so the sweep reads no segment. The order is total:
// distance; at equal distance exits first; then the segment's entry, exit, κ and κ·C. Events
// that tie in all of them are copies of one segment, so the result depends on the set of
// segments only, not on the order in which the particle pass pushed them.
//
// One invocation per pixel of PixelLists' region STAGE + 1, in work groups of 64: the pixels
// whose lists the first resolve (volume_resolve_single.comp.glsl) counted and found to fit SLOTS
// and not half of it (stage 0: 2 to 4 segments), so each stage sees only lists of its own length.
// Preceded by volume_fragments.glsl, volume_pieces.glsl and the defines of
// render/VolumeResolve.cpp: STAGE, STAGES (the number of sorted stages), SLOTS = 4·2^STAGE,
// SORTED_MAX = 4·2^(STAGES − 1),
// and LOAD_SLOTS, SORT_EVENTS, SWEEP_EVENTS, the macros below written out for each slot, each
// compare-exchange of render/SortingNetwork.h and each event.

#if SLOTS != (4 << STAGE) || SORTED_MAX != (4 << (STAGES - 1))
#error "stage r of the sorted resolve holds 4·2^r segments"
#endif

layout(local_size_x = 64) in;

layout(r32ui, binding = 0) uniform readonly uimage2D uHeads;
layout(rgba32f, binding = 1) uniform image2D uColor;  // in: overflow (rgb, T); out: the result

// An event is two vec4: h = (distance t along the view ray, +1 entry / −1 exit / 0 empty, the
// segment's entry a, its exit b), world units; s = (κ per world unit, κ·C), the segment's.
// Whether event x comes after event y in the total order (the first component that differs
// decides, h before s).
bool eventAfter(vec4 hx, vec4 sx, vec4 hy, vec4 sy) {
  bvec4 neh = notEqual(hx, hy), gth = greaterThan(hx, hy);
  bvec4 nes = notEqual(sx, sy), gts = greaterThan(sx, sy);
  bool after = false;
  after = nes.w ? gts.w : after;
  after = nes.z ? gts.z : after;
  after = nes.y ? gts.y : after;
  after = nes.x ? gts.x : after;
  after = neh.w ? gth.w : after;
  after = neh.z ? gth.z : after;
  after = neh.y ? gth.y : after;  // exits (−1) before entries (+1)
  after = neh.x ? gth.x : after;
  return after;
}

// Puts events i and j (i < j) in order.
void compareExchange(inout vec4 hi, inout vec4 si, inout vec4 hj, inout vec4 sj) {
  bool swap = eventAfter(hi, si, hj, sj);
  vec4 h = hi, s = si;
  hi = swap ? hj : hi;
  si = swap ? sj : si;
  hj = swap ? h : hj;
  sj = swap ? s : sj;
}

vec4 h[2 * SLOTS];
vec4 s[2 * SLOTS];
#define CX(i, j) compareExchange(h[i], s[i], h[j], s[j])

// Slot k (0 … SLOTS − 1) takes the segment at `node`, or an empty pair of events when the list
// has ended.
#define LOAD_SLOT(k)                                                          \
  if (node != FRAGMENT_LIST_END) {                                            \
    float a = segmentEntry(node);                                             \
    float b, kappa;                                                           \
    vec3 kappaColor;                                                          \
    segmentTerms(node, a, b, kappa, kappaColor);                              \
    h[k] = vec4(a, 1.0f, a, b);                                               \
    h[k + SLOTS] = vec4(b, -1.0f, a, b);                                      \
    s[k] = vec4(kappa, kappaColor);                                           \
    s[k + SLOTS] = s[k];                                                      \
    node = fragmentNext(node);                                                \
  } else {                                                                    \
    h[k] = vec4(infinity, 0.0f, infinity, infinity);                          \
    h[k + SLOTS] = h[k];                                                      \
    s[k] = vec4(0.0f);                                                        \
    s[k + SLOTS] = s[k];                                                      \
  }

// Event k of the sorted 2·SLOTS: the piece since the last event, then the sums' change.
#define SWEEP(k)                                                              \
  if (present > 0 && h[k].x > last) addPiece(color, transmittance, kappa, kappaColor, h[k].x - last); \
  kappa += h[k].y * s[k].x;                                                   \
  kappaColor += h[k].y * s[k].yzw;                                            \
  present += int(h[k].y);                                                     \
  if (present == 0) { /* nothing present: start the sums afresh */            \
    kappa = 0.0f;                                                             \
    kappaColor = vec3(0.0f);                                                  \
  }                                                                           \
  last = h[k].x;

void main() {
  if (gl_GlobalInvocationID.x >= regionCount[STAGE + 1]) return;
  ivec2 px = unpackPixel(pixels[uint(STAGE + 1) * pixelCapacity + gl_GlobalInvocationID.x]);
  uint node = imageLoad(uHeads, px).x;
  const float infinity = uintBitsToFloat(0x7f800000u);
  LOAD_SLOTS
  SORT_EVENTS

  vec3 color = vec3(0.0f);
  float transmittance = 1.0f;
  float kappa = 0.0f;            // Σκ_i of the segments present (per world unit)
  vec3 kappaColor = vec3(0.0f);  // Σκ_i C_i
  int present = 0;
  float last = 0.0f;
  SWEEP_EVENTS
  vec4 overflow = imageLoad(uColor, px);
  imageStore(uColor, px, vec4(color + transmittance * overflow.rgb, transmittance * overflow.a));
}
