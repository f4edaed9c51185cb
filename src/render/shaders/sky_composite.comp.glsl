// sky_composite.comp.glsl — the frame under the sky (render/SkyPass.h). Per pixel, with the
// clouds' premultiplied radiance Lc, opacity A and distance d from the particle passes:
//   background Lb = the sky-view table's in-scattering along the ray, plus the sun's disc
//                   (sunDiscRadiance) through T to the top, or, where the ray meets the ground,
//                   the ground's radiance (groundRadiance, sunlight through the clouds' shadow
//                   exp(−τ) of the sun volume) through T to the ground;
//   L = T(d) Lc + A S(d) + (1 − A) Lb   (S, T from the aerial-perspective volume; seed §5.6),
// with the light shafts' losses ΔL (sky_shafts.glsl, from the shafts volume) taken from S(d) and
// from Lb's in-scattering.
// Writes L into the colour buffer in place (A kept). Needs sky_uniforms.glsl, the sun volume's
// sampling code and sky_shafts.glsl.
layout(local_size_x = 64) in;
layout(std430, binding = 7) buffer Colour { vec4 colour[]; };
layout(std430, binding = 8) readonly buffer Distance { float distanceTo[]; };
uniform sampler3D uSkyView;     // depth 1
uniform sampler3D uAerialInScatter;
uniform sampler3D uAerialTransmittance;
uniform ivec2 uSize;
uniform int uFirstRow;
uniform float uNoDistance;
uniform sampler3D uShaftLoss;  // the light shafts' loss ΔL at the aerial slices, per screen cell
uniform bool uShafts;          // light shafts on (a volume was built and uShaftLoss is filled)

void main() {
  int x = int(gl_GlobalInvocationID.x), row = int(gl_GlobalInvocationID.y);
  int y = uFirstRow + row;
  if (x >= uSize.x || y >= uSize.y) return;
  int i = row * uSize.x + x;
  vec2 uv = (vec2(x, y) + 0.5) / vec2(uSize);
  vec3 d = screenRay(uv);
  float r = length(uEyePlanet), mu = dot(uEyePlanet, d) / r;
  bool ground = rayHitsGround(uAtmosphere, r, mu);
  vec2 skyUv = skyViewUv(d);
  vec2 viewSize = vec2(textureSize(uSkyView, 0).xy);
  vec3 inScatter = texture(uSkyView, vec3(lutTexCoord(skyUv.x, viewSize.x), lutTexCoord(skyUv.y, viewSize.y), 0.5)).rgb;
  vec4 c = colour[i];
  float dist = distanceTo[i];
  bool cloud = c.a > 0.0 && dist < uNoDistance;
  // the light shafts' losses to the ray's end and to the clouds (0 when the shafts are off)
  vec3 lossFar = vec3(0.0), lossNear = vec3(0.0);
  if (uShafts) {
    lossFar = cumulativeAt(uShaftLoss, uv, distanceToAtmosphereEnd(uAtmosphere, r, mu));
    if (cloud) lossNear = cumulativeAt(uShaftLoss, uv, dist);
  }
  inScatter = max(inScatter - lossFar, vec3(0.0));
  vec3 background;
  if (ground) {
    float t = distanceToGround(uAtmosphere, r, mu);
    vec3 g = uEyePlanet + t * d;
    float shadow = cloudSunVisibility(uEyeWorld + t * d);
    vec3 Lg = groundRadiance(uAtmosphere, uTransmittance, uIrradiance, dot(normalize(g), uSun), shadow);
    background = inScatter + transmittanceAlongRay(uAtmosphere, uTransmittance, r, mu, t, true) * Lg;
  } else {
    background = inScatter + transmittanceToTop(uAtmosphere, uTransmittance, r, mu) * sunDiscRadiance(dot(d, uSun));
  }
  vec3 L = background;
  if (cloud) {
    float w = aerialSliceCoordinate(dist);
    vec3 tc = vec3(uv, (max(w, 0.0) + 0.5) / float(AERIAL_SLICES));
    vec3 S = texture(uAerialInScatter, tc).rgb, T = texture(uAerialTransmittance, tc).rgb;
    if (w < 0.0) {  // closer than the first slice: scale toward the camera
      float f = clamp(w + 1.0, 0.0, 1.0);
      S *= f;
      T = mix(vec3(1.0), T, f);
    }
    L = T * c.rgb + c.a * max(S - lossNear, vec3(0.0)) + (1.0 - c.a) * background;
  } else if (c.a > 0.0) {
    L = c.rgb + (1.0 - c.a) * background;
  }
  colour[i] = vec4(L, c.a);
}
