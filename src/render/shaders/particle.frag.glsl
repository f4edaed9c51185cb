// particle.frag.glsl — shades one particle along one view ray with the tables (seed §4.4, §5.4).
// Preceded by cloudlut_geometry.glsl, cloudlut_phase.glsl, cloudlut_sampling.glsl,
// cloudlut_shading.glsl (verbatim, from lut_formats/glsl), particle_common.glsl and
// volume_fragments.glsl.
//
// Output 0 (RGBA32F, blended ONE/SRC_ALPHA for colour, ZERO/SRC_ALPHA for alpha):
//   rgb = radiance scattered toward the camera, a = transmittance of the particle (alpha mode;
//   in volume mode the segment goes to the pixel's fragment list instead, see uVolume);
// output 1 (R32F, blended with MIN): distance from the eye to the particle's first matter.

uniform vec3 uEye;
uniform vec3 uSunDirection;  // world, unit, toward the sun
uniform vec3 uSunColor;
uniform vec3 uSkyColor;
uniform int uTerms;          // bit 0 single, bit 1 multiple, bit 2 ambient

uniform sampler3D uOpticalDepth;
uniform sampler3D uSingle;
uniform sampler3D uMultiple;
uniform vec4 uOpticalDepthDims;  // (N0, N1, N2, N3)
uniform vec4 uSingleDims;
uniform vec4 uMultipleDims;
uniform vec4 uSingleAxes;    // log2 rho at the first and last node of axis 3, theta_s warp, layout flags
uniform vec4 uMultipleAxes;
uniform float uUnitOpticalRadius;    // sigma = extinction * radius of the optical-depth table
uniform int uFirstPhaseKind;         // phaseFunction() kind and parameter of the single table
uniform float uFirstPhaseParam;
uniform float uMinOpacityForDistance;
uniform float uNoDistance;
uniform int uVolume;  // 1: volume-aware blending (store the segment in the pixel's list)

layout(r32ui, binding = 0) uniform coherent uimage2D uHeads;  // volume_fragments.glsl lists

in vec3 vWorld;
flat in int vParticle;

layout(location = 0) out vec4 oColor;
layout(location = 1) out float oDistance;

void main() {
  GpuParticle p = particles[vParticle];
  mat3 toParticle = mat3(p.toParticle[0].xyz, p.toParticle[1].xyz, p.toParticle[2].xyz);
  float rho = p.centerDensity.w;

  // The view ray in world space (unit direction) and in particle space (unnormalised, so that
  // the ray parameter t is the world distance from the eye).
  vec3 dir = normalize(vWorld - uEye);
  vec3 o = toParticle * (uEye - p.centerDensity.xyz);
  vec3 d = toParticle * dir;

  // |o + t d|^2 = 1, in the cancellation-free form.
  float a = dot(d, d);
  float b = dot(o, d);
  float c = dot(o, o) - 1.0;
  float disc = b * b - a * c;
  if (c <= 0.0 || b >= 0.0 || disc <= 0.0) discard;  // eye inside, sphere behind, or a miss
  float q = -b + sqrt(disc);
  float tEnter = c / q;
  float tExit = q / a;

  vec3 S = normalize(o + tEnter * d);
  vec3 v = normalize(d);
  vec3 l = normalize(toParticle * uSunDirection);

  // Optical depth (seed §4.4): tau = rho * sigma * L * mean density, L in unit-sphere units.
  vec2 od = cloudlutSample4D(uOpticalDepth, opticalDepthAxes(S, v), uOpticalDepthDims).xy;
  float chord = chordLength(S, v);
  float tau = particleOpticalDepth(rho, uUnitOpticalRadius, chord, od.x);
  float transmittance = exp(-tau);

  // Single scattering: the mean source of the homogeneous sphere of the ray's mean density,
  // times the phase function of the physical (world-space) scattering angle. Multiple: the
  // mean source of the sphere of density rho. Both carry the ray's own opacity 1 − e^{−τ}.
  float single = 0.0;
  if ((uTerms & 1) != 0) {
    vec4 x = scatteringAxes(S, v, l, rho * od.x, uSingleAxes, float(uSingleDims.w));
    single = phaseFunction(uFirstPhaseKind, dot(dir, uSunDirection), uFirstPhaseParam) *
             singleScatteringFromTable(cloudlutSample4D(uSingle, x, uSingleDims).x, tau);
  }
  float multiple = 0.0;
  if ((uTerms & 2) != 0) {
    vec4 x = scatteringAxes(S, v, l, rho, uMultipleAxes, float(uMultipleDims.w));
    multiple = multipleScatteringFromTable(cloudlutSample4D(uMultiple, x, uMultipleDims).x, tau);
  }
  // Ambient: sky radiance, scaled by the opacity and by f(distance to the first matter).
  vec3 ambient = vec3(0.0);
  if ((uTerms & 4) != 0)
    ambient = uSkyColor * ambientScale(transmittance, od.y);

  float sunlight = p.toParticle[2].w;  // sunlight reaching the particle (occlusion.comp.glsl)
  vec3 radiance = uSunColor * (sunlight * (single + multiple)) + ambient;
  oColor = vec4(radiance, transmittance);
  if (uVolume != 0) {
    uint node = atomicAdd(fragCount, 1u);
    if (node < fragCapacity) {
      storeFragment(node, tEnter, tExit, tau, radiance, imageAtomicExchange(uHeads, ivec2(gl_FragCoord.xy), node));
      oColor = vec4(0.0, 0.0, 0.0, 1.0);  // stored: composited by volume_resolve.comp.glsl
    } else {
      atomicAdd(fragOverflow, 1u);  // no room: alpha-blended into the colour image (fallback)
    }
  }
  oDistance = 1.0 - transmittance >= uMinOpacityForDistance
                  ? tEnter + clamp(od.y, 0.0, 1.0) * (tExit - tEnter)
                  : uNoDistance;
}
