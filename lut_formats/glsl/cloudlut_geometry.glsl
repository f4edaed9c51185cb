// cloudlut_geometry.glsl — the one definition of the LUT parameterization.
//
// Compiled as GLSL by the renderer and as C++ (through GLM, see src/core/Glsl.h) by the baker,
// the CLI and the tests, so that the tables and their users cannot disagree.
// Written in the subset both languages accept: no in/out/inout, float literals with an `f`
// suffix, every function prefixed by CLOUDLUT_FN (`inline` in C++, nothing in GLSL).
//
// Conventions (lut_formats/FORMAT.md, docs): particle space, the particle is the unit sphere.
//   S  entry point of the view ray, |S| = 1
//   v  unit view direction, pointing into the sphere (dot(v, S) < 0)
//   l  unit vector toward the sun
// The tangent frame at S (seed §4.1, fig. 3): z points to the centre (z = -S); x and y are the
// derivatives of S with respect to its zenith and azimuth angles. Unlike a frame built from a
// fixed "up" vector, this frame is finite at the poles (θS = 0, π), where it still depends
// smoothly on φS; the tables store the poles once per φS and the values agree there.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

const float CLOUDLUT_PI = 3.14159265358979f;

// Texture coordinate of the axis fraction x ∈ [0, 1] in a table of n nodes that include both
// ends of the axis: node i sits at x = i / (n - 1) and at the centre of texel i.
CLOUDLUT_FN float lutTexCoord(float x, float n) {
  return (0.5f + clamp(x, 0.0f, 1.0f) * (n - 1.0f)) / n;
}

// atan(y, x) with atan(0, 0) defined as 0 (GLSL leaves it undefined; GPUs may return NaN).
CLOUDLUT_FN float azimuth(float y, float x) {
  return (x == 0.0f && y == 0.0f) ? 0.0f : atan(y, x);
}

// Azimuth φ ∈ [0, 2π) and zenith θ ∈ [0, π] of a unit vector, in radians.
CLOUDLUT_FN vec2 sphericalAngles(vec3 p) {
  float phi = azimuth(p.y, p.x);
  if (phi < 0.0f) phi += 2.0f * CLOUDLUT_PI;
  // atan rather than acos: well conditioned near the poles as well
  return vec2(phi, atan(length(vec2(p.x, p.y)), p.z));
}

// Point of the unit sphere at azimuth φ and zenith θ.
CLOUDLUT_FN vec3 sphericalPoint(float phi, float theta) {
  return vec3(sin(theta) * cos(phi), sin(theta) * sin(phi), cos(theta));
}

// Tangent x axis at the point (φ, θ): dS/dθ, unit length everywhere including the poles.
CLOUDLUT_FN vec3 tangentX(float phi, float theta) {
  return vec3(cos(theta) * cos(phi), cos(theta) * sin(phi), -sin(theta));
}

// Tangent y axis at the point (φ, θ): dS/dφ divided by sin θ, unit length everywhere.
CLOUDLUT_FN vec3 tangentY(float phi) {
  return vec3(-sin(phi), cos(phi), 0.0f);
}

// Direction of zenith θv (from the inward normal -S) and azimuth φv in the frame (x, y, -S).
CLOUDLUT_FN vec3 frameDirection(vec3 x, vec3 y, vec3 S, float phiV, float thetaV) {
  return sin(thetaV) * (cos(phiV) * x + sin(phiV) * y) - cos(thetaV) * S;
}

// The direction of the optical-depth table's chord at the node angles (φS, θS, φv, θv) (seed
// §4.1; radians): frameDirection in the tangent frame of sphericalPoint(φS, θS), the chord's
// entry. The baker lays its nodes out this way (it caches the frame per entry point); the
// renderer's last-matter pass and its CPU reference read the nodes back through it.
CLOUDLUT_FN vec3 opticalDepthNodeDirection(float phiS, float thetaS, float phiV, float thetaV) {
  return frameDirection(tangentX(phiS, thetaS), tangentY(phiS), sphericalPoint(phiS, thetaS), phiV, thetaV);
}

// Angles (φv, θv) of direction v in the frame (x, y, -S); θv ∈ [0, π], φv ∈ [0, 2π).
CLOUDLUT_FN vec2 frameAngles(vec3 x, vec3 y, vec3 S, vec3 v) {
  float vx = dot(v, x);
  float vy = dot(v, y);
  float phiV = azimuth(vy, vx);
  if (phiV < 0.0f) phiV += 2.0f * CLOUDLUT_PI;
  return vec2(phiV, atan(length(vec2(vx, vy)), -dot(v, S)));
}

// Length of the chord of the unit sphere from S along v (unit-sphere units): 2 cos θv.
CLOUDLUT_FN float chordLength(vec3 S, vec3 v) {
  return max(0.0f, -2.0f * dot(S, v));
}

// Optical-depth table angles (φS, θS, φv, θv), seed §4.1: θv ∈ [0, π/2].
CLOUDLUT_FN vec4 opticalDepthAngles(vec3 S, vec3 v) {
  vec3 s = normalize(S);
  vec2 a = sphericalAngles(s);
  vec2 b = frameAngles(tangentX(a.x, a.y), tangentY(a.x), s, v);
  return vec4(a.x, a.y, b.x, min(b.y, 0.5f * CLOUDLUT_PI));
}

// Axis fractions in [0, 1] of the optical-depth table: (φS/2π, θS/π, φv/2π, θv/(π/2)).
CLOUDLUT_FN vec4 opticalDepthAxes(vec3 S, vec3 v) {
  vec4 a = opticalDepthAngles(S, v);
  return vec4(a.x / (2.0f * CLOUDLUT_PI), a.y / CLOUDLUT_PI, a.z / (2.0f * CLOUDLUT_PI),
              a.w / (0.5f * CLOUDLUT_PI));
}

// Light frame at S: the x axis of the optical-depth frame when l is the pole. y = l × S / |l × S|;
// at the poles (S = ±l) any axis perpendicular to l serves, since the light field is symmetric
// about l and the tables hold the same value for every φv there.
CLOUDLUT_FN vec3 lightFrameY(vec3 S, vec3 l) {
  vec3 c = cross(l, S);
  float len = length(c);
  if (len > 1e-6f) return c / len;
  vec3 a = abs(l.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  return normalize(cross(l, a));
}

// Scattering table angles (θS, φv, θv), seed §4.2: θS is the angle between S and l.
CLOUDLUT_FN vec3 scatteringAngles(vec3 S, vec3 v, vec3 l) {
  vec3 s = normalize(S);
  vec3 y = lightFrameY(s, l);
  vec3 x = cross(y, s);
  vec2 b = frameAngles(x, y, s, v);
  return vec3(atan(length(cross(s, l)), dot(s, l)), b.x, b.y);
}

// Density-scale axis: s = log2 ρ mapped linearly from [sMin, sMax] to [0, 1].
CLOUDLUT_FN float densityAxis(float rho, float sMin, float sMax) {
  return clamp((log2(max(rho, 1e-30f)) - sMin) / max(sMax - sMin, 1e-6f), 0.0f, 1.0f);
}

// Nodes concentrated about the middle of an axis: the fraction y ∈ [0, 1] of the physical
// range at the axis fraction x ∈ [0, 1] is y = 1/2 + sinh(w (x − 1/2)) / (2 sinh(w/2)); w = 0 is
// the uniform axis. The node spacing at the middle is w / (2 sinh(w/2)) times the uniform one
// and w/2 · coth(w/2) times it at the ends. Dimensionless.
CLOUDLUT_FN float concentratedFraction(float x, float w) {
  if (w < 1e-4f) return x;
  return 0.5f + sinh(w * (x - 0.5f)) / (2.0f * sinh(0.5f * w));
}

// Inverse of concentratedFraction: the axis fraction x of the physical fraction y ∈ [0, 1].
CLOUDLUT_FN float concentratedAxis(float y, float w) {
  if (w < 1e-4f) return clamp(y, 0.0f, 1.0f);
  return clamp(0.5f + asinh((y - 0.5f) * 2.0f * sinh(0.5f * w)) / w, 0.0f, 1.0f);
}

// Azimuth folded by a mirror symmetry about the plane φ = 0: φ ∈ [0, 2π) → [0, π], radians.
// The homogeneous sphere's light is symmetric about the plane that holds S and l, so the
// scattering tables' mean sources satisfy J(φv) = J(2π − φv) and a folded table stores φv ∈ [0, π].
CLOUDLUT_FN float mirroredAzimuth(float phi) {
  return phi > CLOUDLUT_PI ? 2.0f * CLOUDLUT_PI - phi : phi;
}

// Density-scale axis of n nodes uniform in s = log2 ρ over [sMin, sMax], interpolated linearly
// in ρ between neighbouring nodes: for ρ between the nodes s_i and s_i + h (h = (sMax − sMin)/(n − 1))
// the weight of the upper node is w = (2^{s − s_i} − 1) / (2^h − 1) = (ρ − ρ_i)/(ρ_{i+1} − ρ_i),
// and the axis fraction is (i + w)/(n − 1), so the linear filter of cloudlutSample4D blends the
// two slices with that weight. Exact for stored values affine in ρ: the log2 mean sun
// transmittance of single scattering is, both where it is −σρ·(mean sun path) (thin particles,
// the dark side) and where it tends to a constant (the lit side of dense ones). Dimensionless.
CLOUDLUT_FN float densityAxisLinearInRho(float rho, float sMin, float sMax, float n) {
  float x = densityAxis(rho, sMin, sMax);
  if (n < 2.5f) return x;
  float p = x * (n - 1.0f);
  float i = min(floor(p), n - 2.0f);
  float h = (sMax - sMin) / (n - 1.0f);
  float w = (exp2((p - i) * h) - 1.0f) / max(exp2(h) - 1.0f, 1e-6f);
  return (i + clamp(w, 0.0f, 1.0f)) / (n - 1.0f);
}

// Layout flags of a scattering table (the sum of them is the 4th component of its axes record;
// FORMAT.md, axis flags): φv folded onto [0, π] (mirroredAzimuth), density axis interpolated
// linearly in ρ (densityAxisLinearInRho). Format version 3 bakes set both; 0 is the layout of
// versions 1 and 2 (φv over [0, 2π], density interpolated linearly in log2 ρ).
const float CLOUDLUT_LAYOUT_FOLDED_PHI_V = 1.0f;
const float CLOUDLUT_LAYOUT_LINEAR_IN_RHO = 2.0f;

// Axis fractions of the scattering tables: (θS axis, φv axis, θv/(π/2), density axis), for the
// table's axes record axes = (sMin, sMax, warpS, layout) and its number of density nodes n.
// The θS nodes concentrate about the terminator θS = π/2 (concentratedAxis(θS/π, warpS), warpS
// the table's θS "warp"), where the light of a dense particle changes over an angle ≈ 1/σ; the
// φv axis is φv/π when folded (mirroredAzimuth), φv/2π otherwise; the density axis is
// densityAxisLinearInRho when the layout says so, densityAxis otherwise.
CLOUDLUT_FN vec4 scatteringAxes(vec3 S, vec3 v, vec3 l, float rho, vec4 axes, float n) {
  vec3 a = scatteringAngles(S, v, l);
  bool folded = mod(axes.w, 2.0f) >= 0.5f;
  bool linearInRho = axes.w >= 1.5f;
  float phi = folded ? mirroredAzimuth(a.y) / CLOUDLUT_PI : a.y / (2.0f * CLOUDLUT_PI);
  float d = linearInRho ? densityAxisLinearInRho(rho, axes.x, axes.y, n) : densityAxis(rho, axes.x, axes.y);
  return vec4(concentratedAxis(a.x / CLOUDLUT_PI, axes.z), phi,
              min(a.z, 0.5f * CLOUDLUT_PI) / (0.5f * CLOUDLUT_PI), d);
}
