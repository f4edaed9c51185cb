// sun_volume_build.comp.glsl — fills the sun optical-depth volume (sun_volume.glsl) from the
// particles. Preceded by cloudlut_geometry.glsl, cloudlut_sampling.glsl, cloudlut_shading.glsl,
// particle_common.glsl, sun_volume.glsl, sun_volume_chord.glsl, sun_chord_map.glsl and the
// defines STAGE, SUN_CASCADES_MAX, SUN_FOOTPRINT_MAX and SUN_FIXED_SCALE (render/SunVolume.cpp):
//   STAGE 0  one invocation per particle: for every column of every cascade its bounding sphere
//            shadows, the chord of the column's sun ray through the ellipsoid, its optical depth
//            from the optical-depth table (seed §4.1) and the slope steps of its ramp (addRamp), added as
//            fixed-point integers (order-independent, so the volume does not depend on the
//            order or the timing of the invocations); with uMapChords, the chords are kept in
//            the chord map (sun_chord_map.glsl) for the particle shader;
//   STAGE 2  (before 0, with uMapChords) one invocation per particle: the chords the chord map
//            needs, so that it can be sized before the splat;
//   STAGE 1  one invocation per column: the double prefix sum from the sun side, τ at every
//            slice stored into the volume texture (render/SunVolume.cpp clears the deltas before
//            each splat).

layout(local_size_x = GROUP_SIZE) in;

uniform uint uCount;
uniform vec3 uSun;               // unit, toward the sun (world)
uniform float uSigma;            // unit optical radius β·R of the optical-depth table
uniform sampler3D uOpticalDepth;
uniform vec4 uOpticalDepthDims;
uniform int uCascades;
uniform ivec3 uDims;             // columns Nu, Nv and slices Nw of one cascade
uniform mat4 uToGrid[SUN_CASCADES_MAX];
uniform mat4 uToWorld[SUN_CASCADES_MAX];
uniform int uMapChords;          // 1: fill the chord map (the sun volume; not the zenith volume)
uniform float uChordOuterThird;  // the optical-depth table's chord_outer_third_share (chordMatterShare)

layout(std430, binding = 5) buffer SunDeltas {
  uint footprintOverflow;        // particle-cascade pairs skipped: footprint over SUN_FOOTPRINT_MAX
  uint pad0, pad1, pad2;
  int deltas[];                  // per cascade, column (i, j): Nw + 1 slots, slot m = integer slice m
};

layout(r32f, binding = 2) uniform writeonly image3D uSunTau;

int columnBase(int cascade, int i, int j) {
  return ((cascade * uDims.y + j) * uDims.x + i) * (uDims.z + 1);
}

// The integer amount (fixed point) of a slope step e at slice coordinate w carried by its two
// slices floor(w) and floor(w) + 1 (sunVolumeDeltaSplit).
ivec2 stepAmounts(float w, float e) {
  vec2 split = sunVolumeDeltaSplit(w);
  return ivec2(round(clamp(e * split * SUN_FIXED_SCALE, -1.0e4 * SUN_FIXED_SCALE, 1.0e4 * SUN_FIXED_SCALE)));
}

// Adds the amounts to slices floor(w) and floor(w) + 1. A delta at slice m only changes τ below
// it (k < m), so m ≤ 0 is dropped; the grid holds every particle, so m > Nw is clamped (it
// cannot occur but for rounding).
void addStep(int base, float w, ivec2 amounts) {
  int m = int(floor(w));
  for (int s = 0; s < 2; ++s) {
    int slot = min(m + s, uDims.z);
    if (slot <= 0 || amounts[s] == 0) continue;
    atomicAdd(deltas[base + slot], amounts[s]);
  }
}

// Lays one chord's ramp (sunVolumeRampAt) into the column at `base`: a slope step at each end
// of its thirds (chordMatterSlopeSteps, per unit of the span's share u), e the ramp's mean slope
// τ_c/(wFirst − wFar) per slice.
// The last slot takes what the others leave, so that the integer steps sum to 0 and the slope
// past the chord is 0 (no drift of τ down the column, whatever the rounding).
void addRamp(int base, float wFirst, float wFar, float e) {
  vec4 steps = e * chordMatterSlopeSteps(uChordOuterThird);
  float third = (wFirst - wFar) / 3.0;
  vec4 w = vec4(wFirst, wFirst - third, wFar + third, wFar);
  int sum = 0;
  for (int q = 0; q < 3; ++q) {
    ivec2 amounts = stepAmounts(w[q], steps[q]);
    addStep(base, w[q], amounts);
    sum += amounts.x + amounts.y;
  }
  ivec2 last = stepAmounts(w[3], steps[3]);
  last.y = -sum - last.x;
  addStep(base, w[3], last);
}

// The columns of cascade k that the bounding sphere (centre, reach: world) of a particle
// shadows, clamped to the grid: first column lo and size (columns); false when none.
bool sunFootprint(vec3 centre, float reach, int k, out ivec2 lo, out ivec2 size) {
  vec3 g = (uToGrid[k] * vec4(centre, 1.0)).xyz;
  // Half-widths in (u, v) of the shadow of the bounding sphere: the support function of a
  // sphere of radius `reach` along the rows of the (linear) map.
  vec2 extent = reach * vec2(length(vec3(uToGrid[k][0][0], uToGrid[k][1][0], uToGrid[k][2][0])),
                           length(vec3(uToGrid[k][0][1], uToGrid[k][1][1], uToGrid[k][2][1])));
  lo = max(ivec2(ceil(g.xy - extent)), ivec2(0));
  ivec2 hi = min(ivec2(floor(g.xy + extent)), uDims.xy - 1);
  size = hi - lo + 1;
  return hi.x >= lo.x && hi.y >= lo.y;
}

#if STAGE == 0
void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= uCount) return;
  GpuParticle p = particles[index];
  float rho = p.centerDensity.w;
  if (uMapChords != 0)
    for (int k = 0; k < uCascades; ++k) sunChordFootprints[int(index) * SUN_CASCADES_MAX + k] = ivec4(SUN_CHORDS_NONE);
  if (!(rho > 0.0)) return;
  vec3 centre = p.centerDensity.xyz;
  mat3 toParticle = particleToUnitSphere(p);
  float reach = p.toParticle[1].w;  // bounding-sphere radius (particle_common.glsl)
  for (int k = 0; k < uCascades; ++k) {
    ivec2 lo, size;
    if (!sunFootprint(centre, reach, k, lo, size)) continue;
    if (size.x * size.y > SUN_FOOTPRINT_MAX) {
      atomicAdd(footprintOverflow, 1u);
      continue;
    }
    // its place in the chord map, which STAGE 2 sized to hold every footprint
    int first = -1;
    if (uMapChords != 0) {
      uint need = uint(size.x * size.y);
      uint at = atomicAdd(sunChordsUsed, need);
      if (at + need <= sunChordsCapacity) {
        first = int(at);
        sunChordFootprints[int(index) * SUN_CASCADES_MAX + k] = ivec4(first, lo, size.x | (size.y << 16));
      }
    }
    float dwds = (uToGrid[k] * vec4(uSun, 0.0)).z;  // slices per world unit along the sun ray
    for (int j = lo.y; j < lo.y + size.y; ++j)
      for (int i = lo.x; i < lo.x + size.x; ++i) {
        float tau, wFirst, wFar;
        bool hit = sunColumnChord(uOpticalDepth, uOpticalDepthDims, uSigma, uToWorld[k], dwds, vec2(i, j), centre,
                                  toParticle, rho, uSun, tau, wFirst, wFar);
        if (first >= 0) sunChords[first + (j - lo.y) * size.x + (i - lo.x)] = vec4(hit ? tau : 0.0, wFirst, wFar, 0.0);
        if (!hit) continue;
        addRamp(columnBase(k, i, j), wFirst, wFar, tau / max(wFirst - wFar, 1e-6));
      }
  }
}
#elif STAGE == 2
// The chords the chord map needs this frame (one per footprint column), added into sunChordsUsed.
void main() {
  uint index = gl_GlobalInvocationID.x;
  if (index >= uCount) return;
  GpuParticle p = particles[index];
  if (!(p.centerDensity.w > 0.0)) return;
  uint need = 0u;
  for (int k = 0; k < uCascades; ++k) {
    ivec2 lo, size;
    if (sunFootprint(p.centerDensity.xyz, p.toParticle[1].w, k, lo, size) && size.x * size.y <= SUN_FOOTPRINT_MAX)
      need += uint(size.x * size.y);
  }
  if (need > 0u) atomicAdd(sunChordsUsed, need);
}
#else
void main() {
  int columns = uDims.x * uDims.y;
  int id = int(gl_GlobalInvocationID.x);
  if (id >= columns * uCascades) return;
  int cascade = id / columns, i = id % uDims.x, j = (id / uDims.x) % uDims.y;
  int base = columnBase(cascade, i, j);
  float slope = 0.0, tau = 0.0;
  for (int m = uDims.z; m >= 1; --m) {
    slope += float(deltas[base + m]) / SUN_FIXED_SCALE;
    tau += slope;
    imageStore(uSunTau, ivec3(i, j, cascade * uDims.z + m - 1), vec4(max(tau, 0.0)));
  }
}
#endif
