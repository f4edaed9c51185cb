// particle.frag.glsl — shades one particle along one view ray with the tables (seed §4.4, §5.4).
// Preceded by cloudlut_geometry.glsl, cloudlut_phase.glsl, cloudlut_sampling.glsl,
// cloudlut_shading.glsl (verbatim, from lut_formats/glsl), particle_common.glsl, particle_varyings.glsl,
// particle_chord.glsl, volume_fragments.glsl, sun_volume.glsl, sun_volume_chord.glsl, sun_chord_map.glsl,
// sun_volume_sampling.glsl, zenith_volume_sampling.glsl, diffusion_sampling.glsl,
// cloudlut_detail_noise.glsl, particle_detail.glsl and hidden_fragments.glsl.
// Two lighting models (render/RenderTypes.h, docs/LIGHTING.md): the seed's (kLighting 0) and the
// cloud model (kLighting 1), whose equations are cloudlut_shading.glsl's.
//
// The configuration is compiled in, not passed as uniforms (ParticlePass::programFor injects the
// PARTICLE_* #defines): llvmpipe runs the code of a branch that no fragment takes for every
// fragment all the same, so a branch on a uniform costs what its code costs, and constants let
// the compiler drop what the configuration does not use (docs/BENCHMARKS.md, "Where a
// fragment's time goes").
//
// Output 0 (RGBA32F, blended ONE/SRC_ALPHA for colour, ZERO/SRC_ALPHA for alpha):
//   rgb = radiance scattered toward the camera, a = transmittance of the particle (alpha mode;
//   in volume mode the segment goes to the pixel's fragment list instead, see kVolume);
// output 1 (R32F, blended with MIN): distance from the eye to the particle's first matter.

uniform vec3 uEye;
uniform vec3 uSunDirection;  // world, unit, toward the sun
uniform vec3 uSunColor;
uniform vec3 uSkyColor;       // sky radiance above the horizon (and the seed's ambient)
uniform vec3 uSkyBelowColor;  // sky radiance below the horizon, the ground's return (cloud lighting)
const int kTerms = PARTICLE_TERMS;  // bit 0 single, bit 1 multiple, bit 2 ambient

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
const int kVolume = PARTICLE_VOLUME;  // 1: volume-aware blending (the segment goes to the pixel's list)
const int kLighting = PARTICLE_LIGHTING;  // 0 seed (§4.4, §5.3), 1 cloud
const int kSunlightVolume = PARTICLE_SUNLIGHT_VOLUME;  // 1: sunlight per shading point (sun volume), 0: per particle
const int kZenithVolume = PARTICLE_ZENITH_VOLUME;  // 1: the zenith volume is built (0: no cloud above or below)
const int kDiffusion = PARTICLE_DIFFUSION;  // 1: the diffusion volume is built (0: no field anywhere)
uniform float uLaterAsymmetry; // mean cosine of the later phase function (diffuseTransmittance)
uniform float uDiffusionShare; // share of the multiple light from the diffusion volume where it has a field
uniform float uDiffusionGain;  // the diffusion's calibration (RenderSettings::diffusionGain)

// The multiple table's stored mean source at (S, v, l) and density ρ; below the table's least
// density the source is taken proportional to ρ (it vanishes with the medium).
float multipleSourceAt(vec3 S, vec3 v, vec3 l, float rho) {
  float rhoMin = exp2(uMultipleAxes.x);
  vec4 x = scatteringAxes(S, v, l, max(rho, rhoMin), uMultipleAxes, float(uMultipleDims.w));
  return cloudlutSample4D(uMultiple, x, uMultipleDims).x * min(rho / rhoMin, 1.0);
}

// The multiple table's angular closure K(ρ, μ) (core/AngularClosure.h, docs/LIGHTING.md): the
// Monte Carlo power of orders 2 … N leaving the reference particle toward exit directions μ =
// ω_out · l over the power the own-term model sends there. Nodes uAngularClosureRho.x +
// i·uAngularClosureRho.y in log2 ρ (i < uAngularClosureDims.x), uniform bins of μ over [−1, 1]
// (uAngularClosureDims.y); kMaxAngularClosureAxis² values (core/AngularClosure.h).
// uAngularClosureDims.z is 1 when K closes the own term with its core shadow (ownCoreShadow),
// which brightens it by at most uOwnCoreShadowMax (the closure's own_core_shadow_max).
uniform vec4 uAngularClosureRho;
uniform ivec3 uAngularClosureDims;
uniform float uAngularClosure[256];
uniform float uOwnCoreShadowMax;

// K at the particle's density scale ρ and exit direction μ (dimensionless): the shared
// interpolation (cloudlut_shading.glsl, angularClosurePosition …) of the uniform's values.
float angularClosure(float rho, float mu) {
  int nodes = uAngularClosureDims.x, bins = uAngularClosureDims.y;
  vec2 p = angularClosurePosition(rho, mu, uAngularClosureRho.x, uAngularClosureRho.y, float(nodes), float(bins));
  vec2 cell = angularClosureCell(p, float(nodes), float(bins));
  int s0 = int(cell.x), m0 = int(cell.y);
  int s1 = min(s0 + 1, nodes - 1), m1 = min(m0 + 1, bins - 1);
  vec4 k = vec4(uAngularClosure[s0 * bins + m0], uAngularClosure[s0 * bins + m1], uAngularClosure[s1 * bins + m0],
                uAngularClosure[s1 * bins + m1]);
  return angularClosureBlend(k, p, cell);
}

layout(r32ui, binding = 0) uniform coherent uimage2D uHeads;  // volume_fragments.glsl lists
const int kHidden = PARTICLE_HIDDEN;  // 1: hidden fragments are culled (render/HiddenFragments.h)
#if PARTICLE_HIDDEN
// before the shader: the depth buffer holds the hidden distances of the batches drawn before
layout(early_fragment_tests) in;
#endif

layout(location = 0) out vec4 oColor;
layout(location = 1) out float oDistance;

void main() {
  GpuParticle p = fragmentParticle();
  mat3 toParticle = particleToUnitSphere(p);
  float rho = p.centerDensity.w;

  // The view ray in world space (unit direction) and its chord through the ellipsoid
  // (particle_chord.glsl): o, d in particle space, [tEnter, tExit] in world distance from the eye.
  vec3 dir = normalize(vWorld - uEye);
  vec3 o, d;
  float tEnter, tExit;
  bool inside;
  if (!particleViewChord(uEye, dir, p.centerDensity.xyz, toParticle, o, d, tEnter, tExit, inside)) discard;
  // hidden behind the segments already stored for the pixel (render/HiddenFragments.h)
  float tNear = max(tEnter, 0.0);
  float hiddenFrom = kHidden != 0 ? hiddenBeyond(ivec2(gl_FragCoord.xy)) : uintBitsToFloat(0x7f800000u);
  if (tNear >= hiddenFrom) discard;
  // The part the eye sees, [tNear, tExit], and its share of the chord's length (1 outside).
  float front = inside ? clamp((tExit - tNear) / max(tExit - tEnter, 1e-30), 0.0, 1.0) : 1.0;

  vec3 S = normalize(o + tEnter * d);
  vec3 v = normalize(d);
  vec3 l = normalize(toParticle * uSunDirection);

  // Optical depth (seed §4.4): tau = rho * sigma * L * mean density, L in unit-sphere units.
  // Eye inside (docs/LIGHTING.md, "Camera inside a particle"): the tables hold whole chords, so
  // the front part takes the mean density of its whole chord (the entry S behind the eye, the
  // same direction v): τ_front = front · τ_chord (dimensionless), and everything below (the
  // scattered radiance through 1 − e^{−τ}, the mean scattering point) uses τ_front with the
  // chord's table entries. Exact for a homogeneous particle.
  vec3 od = cloudlutSample4D(uOpticalDepth, opticalDepthAxes(S, v), uOpticalDepthDims).xyz;
  float chord = chordLength(S, v);
  float tau = front * particleOpticalDepth(rho, uUnitOpticalRadius, chord, od.x);
  tau *= particleDetailFactor(uEye, dir, tNear, tExit);  // detail noise: particle_detail.glsl
  float transmittance = exp(-tau);

  // Where the light is scattered on average along the chord (world point): its first matter,
  // then the e^{−τt}-weighted mean of the stretch up to its last matter. The first matter is the
  // texture's channel 1, a share of the whole chord from its entry, at world distance
  // tEnter + od.y·(tExit − tEnter); inside, the seen part [tNear, tExit] keeps what of that empty
  // stretch the eye has not yet passed (none once past it), so the point does not jump as the eye
  // enters (docs/LIGHTING.md, "Camera inside a particle"). The last matter is channel 2
  // (core/LastMatter.h), a share of the whole chord; the empty stretch after it, 1 − last, is of
  // the seen part 1/front times as much.
  float firstMatter = clamp(od.y, 0.0, 1.0);
  if (inside)
    firstMatter = clamp((tEnter + firstMatter * (tExit - tEnter) - tNear) / max(tExit - tNear, 1e-30), 0.0, 1.0);
  float lastMatter = 1.0 - min((1.0 - clamp(od.z, 0.0, 1.0)) / max(front, 1e-6), 1.0 - firstMatter);
  float tMean = tNear + (tExit - tNear) * meanScatteringShare(firstMatter, lastMatter, tau);
  vec3 xMean = uEye + dir * tMean;

  // Sunlight reaching the particle: per particle from the occlusion pass (seed §5.3), or at the
  // mean scattering point from the sun volume, less the particle's own chord there.
  float sunlight = p.toParticle[2].w;
  vec4 sunTau = vec4(0.0);  // read only where the configuration uses it
  if (kLighting != 0 || kSunlightVolume != 0)
    sunTau = sunOpticalDepths(xMean, vParticle, p.centerDensity.xyz, toParticle, rho, uOpticalDepth,
                              uOpticalDepthDims, uUnitOpticalRadius);
  float tauOutside = kSunlightVolume != 0 ? sunTau.x : 0.0;
  if (kSunlightVolume != 0) sunlight = exp(-tauOutside);

  // Single scattering: the mean source of the homogeneous sphere of the ray's mean density
  // (cloud model with the sun volume: or the particle's own sun transmittance at the mean
  // scattering point, whichever is larger, singleSunTransmittance), times the phase function of
  // the physical (world-space) scattering angle, times the ray's own opacity 1 − e^{−τ}.
  float single = 0.0;
  if ((kTerms & 1) != 0) {
    vec4 x = scatteringAxes(S, v, l, rho * od.x, uSingleAxes, float(uSingleDims.w));
    float source = singleSourceFromTable(cloudlutSample4D(uSingle, x, uSingleDims).x);
    if (kLighting != 0 && kSunlightVolume != 0) source = singleSunTransmittance(source, sunTau.y - sunTau.x);
    single = phaseFunction(uFirstPhaseKind, dot(dir, uSunDirection), uFirstPhaseParam) * chordOpacity(tau) * source;
  }
  // Multiple scattering, per unit sun irradiance, already lit (the sunlight factor included).
  //   seed:  the mean source of the particle's sphere at ρ, times the sunlight;
  //   cloud: the particle's sphere at the ray's density ρ·T̄, closed per exit direction, darkened
  //          by the particle's own core shadow, lit by
  //          the larger of the direct and the diffuse transmittance through the cloud toward the
  //          sun, blended with the cloud sphere of the local cloud around the mean scattering
  //          point (localCloudAlongSun, cloudSphereEntry, cloudSphereDensity), lit the same way
  //          through the cloud beyond it, by the share of the local column that is not the
  //          particle's own.
  float multiple = 0.0;
  if ((kTerms & 2) != 0) {
    if (kLighting == 0) {
      vec4 x = scatteringAxes(S, v, l, rho, uMultipleAxes, float(uMultipleDims.w));
      multiple = sunlight * multipleScatteringFromTable(cloudlutSample4D(uMultiple, x, uMultipleDims).x, tau);
    } else {
      float lit = max(sunlight, diffuseTransmittance(tauOutside, uLaterAsymmetry));
      // the particle's own term, its light sent out by direction as the reference particle's
      // (angularClosure at its exit direction −v·l)
      float own = lit * multipleScatteringFromTable(multipleSourceAt(S, v, l, rho * od.x), tau) *
                  angularClosure(rho, -dot(dir, uSunDirection));
      // darkened where the particle's core shadows x̄ more than the table's sphere would, and
      // brightened (by at most uOwnCoreShadowMax) where less (ownCoreShadow; only with a closure
      // baked for it, uAngularClosureDims.z)
      if (kSunlightVolume != 0 && uAngularClosureDims.z != 0)
        own *= ownCoreShadow(sunTau.y - sunTau.x,
                             homogeneousOwnSunDepth(toParticle * (xMean - p.centerDensity.xyz), l, rho * od.x,
                                                    uUnitOpticalRadius),
                             uLaterAsymmetry, uOwnCoreShadowMax);
      // the cloud sphere: the local cloud's column (localCloudAlongSun), less the particle's own
      // chords, weighs it (less 0.01: a cloud that thin is none, and reads at three points
      // differ by the volume's fixed-point rounding, ~10⁻³); the cloud beyond the window toward
      // the sun shadows it
      vec3 local = localCloudAlongSun(xMean, sunTau.y);
      float weight = cloudScaleWeight(max(local.y - (sunTau.z - sunTau.w) - 0.01, 0.0), local.y);
      if (weight > 0.0) {
        vec3 entry = cloudSphereEntry(local.x, local.y, dir, uSunDirection);
        float rhoCloud = cloudSphereDensity(max(local.y, tau), uUnitOpticalRadius);
        float shadow = directOrDiffuseTransmittance(local.z, uLaterAsymmetry);
        float cloud = shadow * multipleScatteringFromTable(multipleSourceAt(entry, dir, uSunDirection, rhoCloud), tau);
        multiple = mix(own, cloud, weight);
      } else {
        multiple = own;
      }
      // the diffusion volume's share of the multiple light, where it has a field
      // (diffusionShareOfMultiple): the diffuse field at x̄ scattered toward the camera
      // (diffusedRadiance) times the chord's opacity, times the diffusion's gain. In the particle
      // that holds the eye the share falls with the square of the seen part of the chord,
      // `front` (1 outside and as the eye enters, so no step): the tables' term holds its short
      // front segment better (docs/LIGHTING.md, "Camera inside a particle").
      float presence = 0.0, beside = 0.0;
      vec4 field = vec4(0.0);
      if (kDiffusion != 0) field = diffusionFieldAt(xMean, presence, beside);
      presence *= front * front;
      if (presence > 0.0) {
        float diffused = uDiffusionGain * chordOpacity(tau) * diffusedRadiance(field.x, field.yzw, -dir, uLaterAsymmetry);
        // a particle the sun column calls alone may stand beside a cloud (cloudBesideWeight)
        float inCloud = max(weight, beside);
        multiple = mix(multiple, diffused,
                       presence * diffusionShareOfMultiple(uDiffusionShare, inCloud, dot(dir, uSunDirection)));
      }
    }
  }
  // Ambient: the sky's radiance, scaled by the crease factor of the first matter (seed); or
  // (cloud) the opacity times the field at the mean scattering point under a sky of uSkyColor
  // above the horizon and uSkyBelowColor below it, from the cloud's vertical optical depths there
  // (the zenith volume; layeredSkyAmbient, = uniformSkyAmbient · sky when the two are equal).
  vec3 ambient = vec3(0.0);
  if ((kTerms & 4) != 0) {
    if (kLighting == 0) {
      ambient = uSkyColor * ambientScale(transmittance, od.y);
    } else {
      vec2 vertical = kZenithVolume != 0 ? zenithOpticalDepths(xMean) : vec2(0.0);
      float share = skyAboveShare(vertical.x, vertical.y, uLaterAsymmetry, dir.y);
      ambient = layeredSkyAmbient(tau, share, uSkyColor, uSkyBelowColor);
    }
  }

  vec3 radiance = uSunColor * (sunlight * single + multiple) + ambient;
  oColor = vec4(radiance, transmittance);
  if (kVolume != 0) {
    uint node = atomicAdd(fragCount, 1u);
    if (node < fragCapacity) {
      uint next = imageAtomicExchange(uHeads, ivec2(gl_FragCoord.xy), node);
      storeFragment(node, tNear, tExit, tau, radiance, next);
      // counted while the pixel hides nothing yet: a larger D would hide less
      if (kHidden != 0 && isinf(hiddenFrom)) addFrontSegment(ivec2(gl_FragCoord.xy), tExit, tau);
      if (next == FRAGMENT_LIST_END && regionCount[0] < pixelCapacity)  // the pixel's first: list it
        pixels[atomicAdd(regionCount[0], 1u)] = packPixel(ivec2(gl_FragCoord.xy));
      oColor = vec4(0.0, 0.0, 0.0, 1.0);  // stored: composited by the resolves (render/VolumeResolve.h)
    } else {
      atomicAdd(fragOverflow, 1u);  // no room: alpha-blended into the colour image (fallback)
    }
  }
  oDistance = 1.0 - transmittance >= uMinOpacityForDistance
                  ? tNear + firstMatter * (tExit - tNear)
                  : uNoDistance;
}
