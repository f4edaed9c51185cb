// sky_uniforms.glsl — what every dispatch of the sky pass (render/SkyPass.h) reads. Follows the
// shared atmosphere GLSL.
uniform AtmosphereParameters uAtmosphere;
uniform sampler3D uTransmittance;   // atmosphere_transmittance
uniform sampler3D uMultiple;        // atmosphere_multiple_scattering
uniform sampler3D uIrradiance;      // atmosphere_irradiance
uniform vec3 uEyePlanet;            // the camera relative to the planet's centre, m
uniform vec3 uEyeWorld;             // the camera in the world, m
uniform vec3 uSun;                  // unit, toward the sun
uniform float uMsWeight;            // 1 = all orders, 0 = single scattering (--sky-orders 1)
uniform vec3 uForward, uRight, uUp; // camera frame; uRight and uUp scaled by the half-field's tangents

// The unit view ray through screen point uv ∈ [0, 1]² (v = 0 the top row), as CameraFrame.
vec3 screenRay(vec2 uv) {
  return normalize(uForward + (2.0 * uv.x - 1.0) * uRight + (1.0 - 2.0 * uv.y) * uUp);
}

// The sky-view table's local frame at the camera: zenith, the sun's horizontal direction, and
// the horizontal direction 90° from it.
vec3 skyZenith() { return normalize(uEyePlanet); }
vec3 skySunHorizontal() {
  vec3 z = skyZenith();
  vec3 h = uSun - z * dot(uSun, z);
  return dot(h, h) > 1e-12 ? normalize(h) : (abs(z.x) < 0.9 ? normalize(cross(z, vec3(1, 0, 0))) : normalize(cross(z, vec3(0, 0, 1))));
}

// Elevation of the geometric horizon at the camera, rad (≤ 0).
float skyHorizonElevation() {
  return -acos(clamp(uAtmosphere.bottomRadius / length(uEyePlanet), 0.0, 1.0));
}

// Sky-view parameterisation (Hillaire 2020, §5.3): u = azimuth from the sun's vertical / π
// (the sky is mirror-symmetric about it), v splits at the horizon, each half a square root of
// the elevation's distance to the horizon, so texels crowd about the horizon.
vec2 skyViewUv(vec3 d) {
  vec3 z = skyZenith(), sx = skySunHorizontal(), sy = cross(z, sx);
  float e = asin(clamp(dot(d, z), -1.0, 1.0)), eh = skyHorizonElevation();
  float phi = atan(abs(dot(d, sy)), dot(d, sx));
  float v = e >= eh ? 0.5 + 0.5 * sqrt((e - eh) / (0.5 * CLOUDLUT_PI - eh))
                    : 0.5 - 0.5 * sqrt((eh - e) / (0.5 * CLOUDLUT_PI + eh));
  return vec2(phi / CLOUDLUT_PI, v);
}

vec3 skyViewDirection(vec2 uv) {
  vec3 z = skyZenith(), sx = skySunHorizontal(), sy = cross(z, sx);
  float eh = skyHorizonElevation();
  float e = uv.y >= 0.5 ? eh + (0.5 * CLOUDLUT_PI - eh) * pow(2.0 * uv.y - 1.0, 2.0)
                        : eh - (0.5 * CLOUDLUT_PI + eh) * pow(1.0 - 2.0 * uv.y, 2.0);
  float phi = uv.x * CLOUDLUT_PI;
  return cos(e) * (cos(phi) * sx + sin(phi) * sy) + sin(e) * z;
}
