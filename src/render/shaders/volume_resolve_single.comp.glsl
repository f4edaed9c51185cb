// volume_resolve_single.comp.glsl — the first of the resolves of volume-aware blending (seed §5.5):
// one invocation per pixel the particle pass listed (PixelLists' region 0), in work groups of 64.
// It counts the pixel's list, composites a list of one segment itself, and hands each longer list
// to the region of the sorted resolve whose SLOTS fit it (volume_resolve_sorted.comp.glsl, stage
// r in region r + 1: lists of (2^(r+1), 2^(r+2)] segments, the first stage from 2) or, beyond
// uShortList segments, to the chunked resolve (volume_resolve.comp.glsl, the last region).
//
// A lone segment is a single piece (volume_pieces.glsl): it scatters R (its radiance) and passes
// e^{−τ}; the sweep of the sorted resolve would make the same one piece with the same arithmetic.
// A single particle covers most of its pixels alone, and llvmpipe runs a sorting network's code
// for every invocation of the program that holds it, so these pixels skip it.
//
// Preceded by volume_fragments.glsl, volume_pieces.glsl and the defines of
// render/VolumeResolve.cpp: STAGES (the number of sorted stages), SORTED_MAX = 4·2^(STAGES − 1).

layout(local_size_x = 64) in;

layout(r32ui, binding = 0) uniform readonly uimage2D uHeads;
layout(rgba32f, binding = 1) uniform image2D uColor;  // in: overflow (rgb, T); out: the result
uniform int uShortList;  // longer lists go to the chunked resolve (RenderSettings::volumeShortList)

void main() {
  if (gl_GlobalInvocationID.x >= regionCount[0]) return;
  ivec2 px = unpackPixel(pixels[gl_GlobalInvocationID.x]);
  uint node = imageLoad(uHeads, px).x;
  // the list's length L, counted up to one past the longest sorted
  int length = 0;
  for (uint n = node; n != FRAGMENT_LIST_END && length <= SORTED_MAX; n = fragmentNext(n)) ++length;
  if (length > 1 || length > uShortList) {
    int region = length > uShortList ? STAGES + 1 : 1 + clamp(findMSB(length - 1) - 1, 0, STAGES);
    pixels[uint(region) * pixelCapacity + atomicAdd(regionCount[region], 1u)] = packPixel(px);
    return;
  }
  vec3 color = vec3(0.0f);
  float transmittance = 1.0f;
  if (length == 1) {
    float a = segmentEntry(node);
    float b, kappa;
    vec3 kappaColor;
    segmentTerms(node, a, b, kappa, kappaColor);
    addPiece(color, transmittance, kappa, kappaColor, b - a);
  }
  vec4 overflow = imageLoad(uColor, px);
  imageStore(uColor, px, vec4(color + transmittance * overflow.rgb, transmittance * overflow.a));
}
