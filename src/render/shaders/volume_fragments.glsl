// volume_fragments.glsl — the per-pixel fragment lists of volume-aware blending: the particle
// pass (particle.frag.glsl) pushes each particle's segment onto its pixel's list, the resolve
// (volume_resolve.comp.glsl) composites the lists. Preceded by the defines of
// render/VolumeResolve.cpp, which sizes the node pool: FRAGMENT_NODE_WORDS (words per node).
//
// The resolves visit only the pixels in PixelLists (below), not the whole tile.
//
// Node layout (FRAGMENT_NODE_WORDS = 7 words): entry and exit distance along the view ray (world
// units), optical depth τ, radiance r, g, b scattered toward the camera (premultiplied), index of
// the next node of the pixel's list (FRAGMENT_LIST_END ends it). The heads are an r32ui image.

#if FRAGMENT_NODE_WORDS < 7
#error "a fragment node holds seven words"
#endif

const uint FRAGMENT_LIST_END = 0xffffffffu;

layout(std430, binding = 2) buffer Fragments {
  uint fragCount;        // nodes asked for (may exceed the capacity)
  uint fragCapacity;     // nodes the pool holds
  uint fragOverflow;     // fragments that found no room (alpha-blended by the particle pass)
  uint truncatedPixels;  // pixels with more than MAX_SEGMENTS segments (counted by the resolve)
  uint nodes[];
};

void storeFragment(uint node, float entry, float exitDistance, float tau, vec3 radiance, uint next) {
  uint base = node * uint(FRAGMENT_NODE_WORDS);
  nodes[base] = floatBitsToUint(entry);
  nodes[base + 1u] = floatBitsToUint(exitDistance);
  nodes[base + 2u] = floatBitsToUint(tau);
  nodes[base + 3u] = floatBitsToUint(radiance.r);
  nodes[base + 4u] = floatBitsToUint(radiance.g);
  nodes[base + 5u] = floatBitsToUint(radiance.b);
  nodes[base + 6u] = next;
}

#ifdef FRAGMENT_READS
// The resolves' reads (render/VolumeResolve.cpp defines FRAGMENT_READS for them alone): the pool
// through a buffer texture over the same buffer (R32UI, one texel per word, the four counters
// first; VolumeResolve binds it to texture unit 0; why: render/GpuStorage.h, BufferTexels).
uniform usamplerBuffer uFragmentNodeWords;
const int FRAGMENT_COUNTER_WORDS = 4;
// Word w of node `node`.
uint fragmentWord(uint node, uint w) {
  return texelFetch(uFragmentNodeWords, FRAGMENT_COUNTER_WORDS + int(node * uint(FRAGMENT_NODE_WORDS) + w)).x;
}

// (entry, exit, τ) of a node, its radiance, and the next node.
vec3 fragmentSpan(uint node) {
  return uintBitsToFloat(uvec3(fragmentWord(node, 0u), fragmentWord(node, 1u), fragmentWord(node, 2u)));
}
vec3 fragmentRadiance(uint node) {
  return uintBitsToFloat(uvec3(fragmentWord(node, 3u), fragmentWord(node, 4u), fragmentWord(node, 5u)));
}
uint fragmentNext(uint node) { return fragmentWord(node, 6u); }
#endif

// PIXEL_LIST_REGIONS lists of pixels of the tile, packed x | y << 16, in regions of pixelCapacity
// words (the tile's pixel count, set with the counters before each draw): region 0, the pixels
// whose list the particle pass started (one entry per pixel with a list); each next region, those
// the sorted resolve of the region before left for a longer one; the last, those left to the
// chunked resolve (render/VolumeResolve.h). regionCount[r] entries of region r are used.
layout(std430, binding = 4) buffer PixelLists {
  uint regionCount[PIXEL_LIST_REGIONS];
  uint pixelCapacity;
  uint pixels[];
};
uint packPixel(ivec2 px) { return uint(px.x) | (uint(px.y) << 16); }
ivec2 unpackPixel(uint word) { return ivec2(int(word & 0xffffu), int(word >> 16)); }
