// sky_aerial_slices.glsl — where the aerial-perspective volume's slices lie along a view ray
// (GLSL only; needs AERIAL_SLICES). Used by the aerial pass that fills the volume, the light
// shafts and the composite that read it.
uniform float uAerialMax;  // m, the aerial volume's reach

// Distance of slice k, m: d_k = uAerialMax ((k + 1) / AERIAL_SLICES)² (slices crowd near the
// camera, where the air's in-scattering changes fastest relative to the distance).
float aerialSliceDistance(int k) {
  float f = float(k + 1) / float(AERIAL_SLICES);
  return uAerialMax * f * f;
}

// The slice coordinate of distance t (m): k at d_k, −1 at the camera, AERIAL_SLICES − 1 at the
// reach and beyond (the inverse of aerialSliceDistance).
float aerialSliceCoordinate(float t) {
  return sqrt(clamp(t / uAerialMax, 0.0, 1.0)) * float(AERIAL_SLICES) - 1.0;
}
