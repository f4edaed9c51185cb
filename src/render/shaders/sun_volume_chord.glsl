// sun_volume_chord.glsl — one particle's chord along one column of the sun optical-depth
// volume (sun_volume.glsl), shared by the splat (sun_volume_build.comp.glsl) and by the
// particle shader, which removes the particle's own ramp from the volume exactly as the splat
// laid it (GLSL only; requires cloudlut_geometry/sampling/shading.glsl).

// The chord of the sun ray of column (i, j) of a cascade (toWorld: grid → world) through the
// ellipsoid x = centre + M·p (toParticle = M⁻¹): false when it misses. Otherwise its optical
// depth tauChord (seed eq. 1, from the optical-depth table: ρ·σ·L·T̄) and the slice coordinates
// of its first matter (wFirst, on the sun side) and of its last matter (wFar < wFirst), from
// the table's channels 1 and 2 (the renderer's texture holds the derived last matter,
// core/LastMatter.h).
// dwds: slices per world unit along the sun.
bool sunColumnChord(sampler3D opticalDepth, vec4 opticalDepthDims, float sigma, mat4 toWorld, float dwds, vec2 ij,
                    vec3 centre, mat3 toParticle, float rho, vec3 sun, out float tauChord, out float wFirst,
                    out float wFar) {
  tauChord = 0.0;
  wFirst = 0.0;
  wFar = 0.0;
  vec3 dl = toParticle * sun;
  vec3 o = toParticle * ((toWorld * vec4(ij, 0.0, 1.0)).xyz - centre);
  float a = dot(dl, dl), b = dot(o, dl), c = dot(o, o) - 1.0;
  float disc = b * b - a * c;
  if (disc <= 0.0) return false;
  float root = sqrt(disc);
  float sSun = (-b + root) / a, sFar = (-b - root) / a;  // world distances along l from w = 0
  vec3 S = normalize(o + sSun * dl);
  vec3 v = -normalize(dl);
  vec3 od = cloudlutSample4D(opticalDepth, opticalDepthAxes(S, v), opticalDepthDims).xyz;
  tauChord = particleOpticalDepth(rho, sigma, chordLength(S, v), od.x);
  float wSun = sSun * dwds, wExit = sFar * dwds;
  float first = clamp(od.y, 0.0, 1.0), last = clamp(od.z, first, 1.0);  // channels 1 and 2 (core/LastMatter.h)
  wFirst = wSun - first * (wSun - wExit);
  wFar = wSun - last * (wSun - wExit);
  // At least one slice long, about the same middle, within the chord: the volume resolves no
  // less, and a shorter ramp's steps would cancel in fixed point.
  if (wFirst - wFar < 1.0) {
    float middle = 0.5 * (wFirst + wFar);
    wFirst = min(middle + 0.5, wSun);
    wFar = max(wFirst - 1.0, wExit);
  }
  return tauChord > 0.0;
}
