// particle_count.frag.glsl — counts the fragments the particle pass will store (volume-aware
// blending plans its screen tiles from them, render/VolumeResolve.h): every fragment whose view
// ray meets its particle's ellipsoid (particle_chord.glsl, the particle pass's own test) adds
// 1 to its pixel. Preceded by particle_common.glsl, particle_varyings.glsl and particle_chord.glsl.
//
// Output 0 (RGBA32F, blended ONE/ONE): r = the pixel's count (exact up to 2^24);
// output 1 (R32F, blended with MIN): uNoDistance, which leaves the cleared distance as it was.

uniform vec3 uEye;
uniform float uNoDistance;

layout(location = 0) out vec4 oCount;
layout(location = 1) out float oDistance;

void main() {
  GpuParticle p = fragmentParticle();
  mat3 toParticle = particleToUnitSphere(p);
  vec3 o, d;
  float tEnter, tExit;
  bool inside;
  if (!particleViewChord(uEye, normalize(vWorld - uEye), p.centerDensity.xyz, toParticle, o, d, tEnter, tExit, inside))
    discard;
  oCount = vec4(1.0, 0.0, 0.0, 0.0);
  oDistance = uNoDistance;
}
