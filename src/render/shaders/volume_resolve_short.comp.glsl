// volume_resolve_short.comp.glsl — volume-aware blending (seed §5.5, eqs. 15–17) of the pixels
// whose lists hold at most uShortList segments: most pixels of a frame (one, or a few
// overlapping particles). The same pieces as volume_resolve.comp.glsl (volume_pieces.glsl): the
// segments are cut at every entry and exit, the extinctions and extinction-weighted sources of
// the segments present in a piece add, the pieces are composited front to back, then the
// fragments that found no room in the pool (overflow, alpha-blended by the particle pass).
//
// Without arrays (a GL that keeps them in memory, llvmpipe, pays for them in every invocation):
// the sweep finds each next event (an entry or an exit) by walking the list again for the
// smallest event after the last one taken, in a total order (distance; at equal distance exits
// first; then the segment's key, compareKeys), and keeps the running sums of κ and κ·C as the
// events pass. So the result depends on the set of segments only, not on the order the particle
// pass pushed them; a list of L segments costs 2L walks of it. A longer list is appended to
// PixelLists for volume_resolve.comp.glsl.
//
// One invocation per pixel that the particle pass listed (PixelLists: the pixels with a list;
// the others keep their colour), in work groups of 64. Preceded by volume_fragments.glsl and
// volume_pieces.glsl.

layout(local_size_x = 64) in;

layout(r32ui, binding = 0) uniform readonly uimage2D uHeads;
layout(rgba32f, binding = 1) uniform image2D uColor;  // in: overflow (rgb, T); out: the result
uniform int uShortList;  // the longest list resolved here (RenderSettings::volumeShortList)

// An event: the entry (isEntry) or the exit at distance t of the segment (a, node).
struct Event {
  float t;
  bool isEntry;
  float a;
  uint node;
};

// −1, 0 or +1 as event x comes before, ties with or comes after event y.
int compareEvents(Event x, Event y) {
  if (x.t != y.t) return x.t < y.t ? -1 : 1;
  if (x.isEntry != y.isEntry) return x.isEntry ? 1 : -1;  // exits first
  return compareKeys(x.a, x.node, y.a, y.node);
}

void main() {
  if (gl_GlobalInvocationID.x >= touchedCount) return;
  ivec2 px = unpackPixel(pixels[gl_GlobalInvocationID.x]);
  uint head = imageLoad(uHeads, px).x;
  int count = 0;
  for (uint node = head; node != FRAGMENT_LIST_END && count <= uShortList; node = fragmentNext(node)) ++count;
  if (count > uShortList) {
    pixels[pixelCapacity + atomicAdd(longCount, 1u)] = packPixel(px);
    return;
  }

  vec3 color = vec3(0.0f);
  float transmittance = 1.0f;
  float kappa = 0.0f;            // Σκ_i of the segments present (per world unit)
  vec3 kappaColor = vec3(0.0f);  // Σκ_i C_i
  int present = 0;
  Event last = Event(0.0f, false, 0.0f, 0u);
  for (int step = 0; step < 2 * count; ++step) {
    // The smallest event after `last` (any, on the first step), and how many events tie with it
    // (nodes that hold the same segment).
    Event next = Event(0.0f, false, 0.0f, 0u);
    int ties = 0;
    for (uint node = head; node != FRAGMENT_LIST_END; node = fragmentNext(node)) {
      float a = segmentEntry(node);
      float b = segmentExit(node, a);
      for (int e = 0; e < 2; ++e) {
        Event candidate = Event(e == 0 ? a : b, e == 0, a, node);
        if (step > 0 && compareEvents(candidate, last) <= 0) continue;
        int c = ties == 0 ? -1 : compareEvents(candidate, next);
        if (c < 0) {
          next = candidate;
          ties = 1;
        } else if (c == 0) {
          ++ties;
        }
      }
    }
    if (ties == 0) break;
    if (present > 0 && next.t > last.t) addPiece(color, transmittance, kappa, kappaColor, next.t - last.t);
    float b, k;
    vec3 kc;
    segmentTerms(next.node, next.a, b, k, kc);
    for (int r = 0; r < ties; ++r) {
      if (next.isEntry) {
        kappa += k;
        kappaColor += kc;
        ++present;
      } else {
        kappa -= k;
        kappaColor -= kc;
        if (--present == 0) {  // nothing present: start the sums afresh
          kappa = 0.0f;
          kappaColor = vec3(0.0f);
        }
      }
    }
    last = next;
  }
  vec4 overflow = imageLoad(uColor, px);
  imageStore(uColor, px, vec4(color + transmittance * overflow.rgb, transmittance * overflow.a));
}
