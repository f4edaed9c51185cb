// sun_chord_map.glsl — the sun volume's chord map (GLSL only): every particle's chords along
// the columns of its footprint, as the splat (sun_volume_build.comp.glsl) computed and laid them
// into the volume, kept for the frame so that the particle shader removes a particle's own ramp
// (sunOpticalDepths, sun_volume_sampling.glsl) by reading the splat's chords instead of
// computing them again: the two agree by construction, and a fragment's removal costs four
// buffer reads instead of four ray-ellipsoid intersections and optical-depth table lookups.
// Requires SUN_CASCADES_MAX.

// Per particle and cascade (index particle · SUN_CASCADES_MAX + cascade), written by the splat:
//   x  its first chord in sunChords[], or SUN_CHORDS_NONE (not splatted into this cascade);
//   y, z  the footprint's first column (i, j);
//   w  its width | height << 16 (columns; the footprint holds at most SUN_FOOTPRINT_MAX).
layout(std430, binding = 9) buffer SunChordFootprints {
  ivec4 sunChordFootprints[];
};
// The chords, one per column of a footprint, rows of constant j after one another: τ of the
// chord (0 when the column's ray misses the particle), wFirst and wFar (sun_volume_chord.glsl).
layout(std430, binding = 10) buffer SunChords {
  uint sunChordsUsed;      // chords handed out this frame
  uint sunChordsCapacity;  // chords the buffer holds after this header
  uint sunChordsPad0, sunChordsPad1;
  vec4 sunChords[];
};

#define SUN_CHORDS_NONE (-2)

// The same two buffers as buffer textures, for the particle shader (SunVolume::bindChordMap; why:
// render/GpuStorage.h, BufferTexels).
uniform isamplerBuffer uSunChordFootprintTexels;  // RGBA32I, one texel per sunChordFootprints[] entry
uniform samplerBuffer uSunChordTexels;            // RGBA32F, texel 0 the header, then sunChords[]

// sunChordFootprints[particle · SUN_CASCADES_MAX + cascade], read as a texel.
ivec4 sunChordFootprintTexel(int particle, int cascade) {
  return texelFetch(uSunChordFootprintTexels, particle * SUN_CASCADES_MAX + cascade);
}
// sunChords[at], read as a texel (after the header's).
vec4 sunChordTexel(int at) { return texelFetch(uSunChordTexels, at + 1); }

// The index in sunChords[] of column ij of footprint fp, or −1 when ij lies outside it (every
// column of SUN_CHORDS_NONE's empty footprint does).
int sunChordIndex(ivec4 fp, ivec2 ij) {
  ivec2 r = ij - fp.yz;
  int width = fp.w & 0xffff, height = fp.w >> 16;
  if (r.x < 0 || r.y < 0 || r.x >= width || r.y >= height) return -1;
  return fp.x + r.y * width + r.x;
}
