// sun_volume_sampling.glsl — reading the sun optical-depth volume (sun_volume.glsl) in a shader
// (GLSL only). Bind it with SunVolume::bind. Requires SUN_CASCADES_MAX, sun_volume.glsl,
// sun_volume_chord.glsl, sun_chord_map.glsl and cascade_columns.glsl, and SUN_CHORD_MAP: 1 when
// the chord map holds every chord of the frame, 0 to compute them (two programs, not a branch:
// llvmpipe runs an untaken branch's texture reads for every fragment all the same). With
// uSunCascades = 0 (no volume built) every point is unshadowed.

uniform sampler3D uSunTau;       // R32F, cascades stacked along the depth; S, T clamp to border 0
uniform int uSunCascades;
uniform ivec3 uSunDims;          // columns Nu, Nv and slices Nw of one cascade
uniform mat4 uSunToGrid[SUN_CASCADES_MAX];
uniform mat4 uSunToWorld[SUN_CASCADES_MAX];
uniform vec3 uSunColumns;        // unit direction of the columns (the sun, raised off the horizon if need be)
uniform float uSunLocalCloud;    // window along the columns that holds one cloud (world units; localCloudColumn)
uniform float uSunChordOuterThird;  // how the splat laid each chord (the table's chord_outer_third_share)

// Optical depth (dimensionless) toward the sun of the particles in front of world point x,
// from the finest cascade whose columns hold x (trilinear; a point outside every cascade is
// unshadowed; above the top slice it takes the top's value, below the bottom the bottom's).
float sunOpticalDepth(vec3 x) {
  vec3 g;
  int k = finestCascadeHolding(uSunToGrid, uSunCascades, uSunDims, x, g);
  return k < 0 ? 0.0 : cascadeSliceAndFarEnd(uSunTau, uSunDims, uSunCascades, k, g).x;
}

// What the volume says of the sunlight at world point x of particle record `particle` (centre,
// toParticle = M⁻¹, density ρ), from the finest cascade whose columns hold x (all dimensionless):
//   x  τ toward the sun from x, less the particle's own ramp as the splat laid it into the four
//      columns and two slices the sample filters (the sunlight reaching x from outside it; the
//      chords from the chord map, or computed as the splat did them);
//   y  τ toward the sun from x, all of it;
//   z  τ of the whole column through x (its far end, slice 0);
//   w  the same column less the particle's own chords (the cloud around the particle along the
//      sun: 0 for a particle alone, up to the fixed-point rounding).
// (0, 0, 0, 0) outside every cascade.
vec4 sunOpticalDepths(vec3 x, int particle, vec3 centre, mat3 toParticle, float rho, sampler3D opticalDepth,
                      vec4 opticalDepthDims, float sigma) {
  vec3 g;
  int k = finestCascadeHolding(uSunToGrid, uSunCascades, uSunDims, x, g);
  if (k < 0) return vec4(0.0);
  vec2 totalAndColumn = cascadeSliceAndFarEnd(uSunTau, uSunDims, uSunCascades, k, g);
  float total = totalAndColumn.x, column = totalAndColumn.y;
  float w = clamp(g.z, 0.0, float(uSunDims.z) - 1.0);
  float dwds = (uSunToGrid[k] * vec4(uSunColumns, 0.0)).z;
  vec2 base = floor(g.xy), f = g.xy - base;
  float w0 = min(floor(w), float(uSunDims.z) - 2.0), fw = w - w0;
  float own = 0.0, ownColumn = 0.0;
#if SUN_CHORD_MAP
  ivec4 footprint = sunChordFootprintTexel(particle, k);
#endif
  for (int n = 0; n < 4; ++n) {
    vec2 corner = vec2(float(n & 1), float(n >> 1));
    float weight = mix(1.0 - f.x, f.x, corner.x) * mix(1.0 - f.y, f.y, corner.y);
    if (weight <= 0.0) continue;
    float tau, wFirst, wFar;
#if SUN_CHORD_MAP
    int at = sunChordIndex(footprint, ivec2(base + corner));
    if (at < 0) continue;  // outside the footprint, or not splatted into this cascade
    vec4 chord = sunChordTexel(at);
    tau = chord.x;
    wFirst = chord.y;
    wFar = chord.z;
    if (!(tau > 0.0)) continue;
#else
    if (!sunColumnChord(opticalDepth, opticalDepthDims, sigma, uSunToWorld[k], dwds, base + corner, centre,
                        toParticle, rho, uSunColumns, tau, wFirst, wFar))
      continue;
#endif
    own += weight * mix(sunVolumeRampAt(tau, wFirst, wFar, w0, uSunChordOuterThird), sunVolumeRampAt(tau, wFirst, wFar, w0 + 1.0, uSunChordOuterThird), fw);
    ownColumn += weight * sunVolumeRampAt(tau, wFirst, wFar, 0.0, uSunChordOuterThird);
  }
  column = max(column, total);
  return vec4(max(total - own, 0.0), total, column, max(column - ownColumn, 0.0));
}

// The local cloud along the sun column through world point x (localCloudColumn): the matter
// within uSunLocalCloud toward and away from the sun, and the optical depth beyond it toward the
// sun, given tauSun, the optical depth toward the sun at x (sunOpticalDepths(...).y).
vec3 localCloudAlongSun(vec3 x, float tauSun) {
  return localCloudColumn(tauSun, sunOpticalDepth(x + uSunLocalCloud * uSunColumns),
                          sunOpticalDepth(x - uSunLocalCloud * uSunColumns));
}

// The local cloud columns (localCloudAlongSun(...).y, dimensionless) through four world points
// beside x across the sun columns: x moved both ways by `offset` (world units) along two
// directions perpendicular to them. Read by cloudBesideWeight.
vec4 localColumnsBeside(vec3 x, float offset) {
  vec3 a = normalize(cross(uSunColumns, abs(uSunColumns.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0)));
  vec3 b = cross(uSunColumns, a);
  vec4 columns;
  for (int k = 0; k < 4; ++k) {
    vec3 y = x + offset * (k < 2 ? a : b) * ((k & 1) == 0 ? 1.0 : -1.0);
    columns[k] = localCloudAlongSun(y, sunOpticalDepth(y)).y;
  }
  return columns;
}
