// particle_chord.glsl — the view ray's chord through a particle's ellipsoid: the one test that
// decides which fragments a particle has, shared by the particle pass (particle.frag.glsl) and
// its fragment count (particle_count.frag.glsl), so that the count is the pass's to the fragment.

// The ray from `eye` along the unit world direction `dir` against the ellipsoid of centre
// `centre` and inverse map `toParticle` (p = toParticle · (x − centre), the unit sphere):
//   o, d            the eye and the direction in particle space (d unnormalised, so that the ray
//                   parameter t is the world distance from the eye);
//   tEnter, tExit   the whole chord (world units from the eye; tEnter ≤ 0 when the eye is inside);
//   inside          the eye inside the ellipsoid.
// |o + t d|² = 1 is a t² + 2 b t + c = 0, its roots taken in the cancellation-free form. False
// (the outputs other than o, d, inside unset) for a miss, or an ellipsoid behind the eye.
bool particleViewChord(vec3 eye, vec3 dir, vec3 centre, mat3 toParticle, out vec3 o, out vec3 d, out float tEnter,
                       out float tExit, out bool inside) {
  o = toParticle * (eye - centre);
  d = toParticle * dir;
  float a = dot(d, d);
  float b = dot(o, d);
  float c = dot(o, o) - 1.0;
  float disc = b * b - a * c;
  inside = c <= 0.0;
  if (disc <= 0.0 || (!inside && b >= 0.0)) return false;
  float q = b < 0.0 ? -b + sqrt(disc) : -b - sqrt(disc);
  tEnter = b < 0.0 ? c / q : q / a;
  tExit = b < 0.0 ? q / a : c / q;
  return true;
}
