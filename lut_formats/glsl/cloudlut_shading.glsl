// cloudlut_shading.glsl — how one particle's view ray is shaded from the table samples
// (seed §4.4), shared by the renderer's shaders and the C++ that checks them.

#ifndef CLOUDLUT_FN
#define CLOUDLUT_FN
#endif

// Optical depth of the ray (dimensionless, seed eq. 1 via the table): ρ·σ·L·mean density, with
// σ the unit optical radius (extinction·radius), L the chord in unit-sphere units.
CLOUDLUT_FN float particleOpticalDepth(float rho, float sigma, float chord, float meanDensity) {
  return rho * sigma * chord * meanDensity;
}

// Opacity 1 − e^{−τ} of a chord of optical depth τ (dimensionless), accurate for small τ too.
CLOUDLUT_FN float chordOpacity(float tau) {
  return tau < 1e-3f ? tau * (1.0f - 0.5f * tau) : 1.0f - exp(-tau);
}

// Storage of the scattering tables (seed eq. 9 for L1, §4.3 for LM). A chord's scattered
// radiance is L = ∫_0^c σ e^{−σt} J(t) dt: its opacity 1 − e^{−σc} times the mean source J̄
// along it (the e^{−σt}-weighted mean of J, sr⁻¹ per unit sun irradiance; for L1 without the
// phase function, the mean sun transmittance). The tables store J̄, which stays finite at
// grazing rays (it tends to the source at the entry point while L → 0); the single table
// stores log2 J̄, since J̄1 falls off exponentially across the terminator of a dense particle
// and the hardware's linear interpolation of log2 J̄1 follows that (geometric interpolation).
// The multiple table stores J̄M itself: it is smooth, peaked toward the sun, and geometric
// interpolation would bias its energy low (measured: −0.2% to −0.5%, against ±0.1% linear).
const float CLOUDLUT_LOG2_SOURCE_FLOOR = -64.0f;  // stored value of J̄1 = 0 (J̄1 < 5e-20)

// The single-scattering table's stored value of a mean source J̄1 ≥ 0 (dimensionless).
CLOUDLUT_FN float singleScatteringToTable(float meanSource) {
  return max(log2(max(meanSource, 1e-30f)), CLOUDLUT_LOG2_SOURCE_FLOOR);
}

// The mean source J̄1 (dimensionless) from the single table's stored value: 2^stored, 0 at the
// floor.
CLOUDLUT_FN float singleSourceFromTable(float stored) {
  return stored <= CLOUDLUT_LOG2_SOURCE_FLOOR ? 0.0f : exp2(stored);
}

// Single-scattered radiance without the phase function, per unit sun irradiance, of a chord of
// optical depth τ, from the single table's stored value: (1 − e^{−τ}) · 2^stored.
CLOUDLUT_FN float singleScatteringFromTable(float stored, float tau) {
  return chordOpacity(tau) * singleSourceFromTable(stored);
}

// Multiply-scattered radiance per unit sun irradiance (sr⁻¹) of a chord of optical depth τ,
// from the multiple table's stored mean source: (1 − e^{−τ}) · J̄M.
CLOUDLUT_FN float multipleScatteringFromTable(float stored, float tau) {
  return chordOpacity(tau) * max(stored, 0.0f);
}

// At runtime (seed §4.4) τ is the particle's optical depth along the ray from the
// optical-depth table: single = P1 · singleScatteringFromTable(J̄1 at ρ·mean density, τ),
// multiple = multipleScatteringFromTable(J̄M at ρ, τ), so an empty ray carries no light and a
// ray as dense as the sphere carries the sphere's. For the tables' own homogeneous sphere of
// density ρ, τ = ρσ · 2 cos θv.

// Scale of the sky radiance for the ambient term (seed §4.4 leaves the function open): the
// ray's opacity, darkened by up to one half where the first matter lies deep along the chord
// (creases) rather than at its entry (edges). firstMatter ∈ [0, 1] is the table's channel 1.
CLOUDLUT_FN float ambientScale(float transmittance, float firstMatter) {
  return (1.0f - transmittance) * (1.0f - 0.5f * clamp(firstMatter, 0.0f, 1.0f));
}

// ---- The cloud lighting model (the renderer's default; docs/LIGHTING.md) -------------------
// The seed's model shades each particle as if it were alone: sunlight from a per-particle
// occlusion estimate, multiple scattering of the particle's own sphere at density ρ, ambient
// scaled by a crease factor. The functions below let the light flow through the cloud: the
// sunlight reaching each shading point comes from the optical depth of the other particles
// toward the sun (the renderer's sun volume), and multiple scattering blends the particle's own
// sphere with the sphere of the cloud around the point.

// Fraction of a homogeneous chord of optical depth τ at which light is scattered toward the
// viewer on average: the e^{−τt}-weighted mean of t ∈ [0, 1], 1/τ − e^{−τ}/(1 − e^{−τ})
// (1/2 for a transparent chord, → 1/τ for an opaque one; dimensionless).
CLOUDLUT_FN float meanScatteringFraction(float tau) {
  if (tau < 1e-3f) return 0.5f - tau / 12.0f;
  float e = exp(-tau);
  return 1.0f / tau - e / (1.0f - e);
}

// Share of a chord (dimensionless, of its length from the entry) at which its light is scattered
// on average: the first matter, then the e^{−τt}-weighted mean (meanScatteringFraction) of the
// stretch up to the last matter. first, last ∈ [0, 1] are shares of the chord; τ its optical depth.
CLOUDLUT_FN float meanScatteringShare(float firstMatter, float lastMatter, float tau) {
  return firstMatter + (lastMatter - firstMatter) * meanScatteringFraction(tau);
}

// Mean sun transmittance J̄1 (dimensionless, the single table's quantity) of a chord of a
// noise particle, from two estimates that each fall short where the other holds:
//   tableSource  J̄1 of the homogeneous sphere at the chord's mean density (the table, exact
//                for a homogeneous particle; low at the rims of an inhomogeneous one, whose
//                thin outskirts pass more sunlight than the sphere of the same mean density);
//   tauOwnAtMean the particle's own optical depth toward the sun at the chord's mean scattering
//                point (the sun volume's ramp of this particle), whose e^{−τ} is the sun
//                transmittance at one point, below the chord's mean of e^{−τ} wherever τ varies
//                along the chord (Jensen's inequality: the mean of a convex function is at
//                least the function of the mean).
// Both are low estimates of the same mean, so the larger is the closer (measured against the
// path tracer: docs/LIGHTING.md, "Single scattering").
CLOUDLUT_FN float singleSunTransmittance(float tableSource, float tauOwnAtMean) {
  return max(tableSource, exp(-max(tauOwnAtMean, 0.0f)));
}

// Ambient radiance per unit sky radiance of a chord of optical depth τ under a uniform sky: a
// non-absorbing medium in an isotropic uniform field holds that field's radiance everywhere,
// so the chord adds exactly the sky it hides, 1 − e^{−τ} (dimensionless).
CLOUDLUT_FN float uniformSkyAmbient(float tau) { return chordOpacity(tau); }

// The ambient under a sky that is not uniform: radiance skyAbove from every direction above the
// horizon, skyBelow (the ground's return) from every direction below it. In a conservative medium
// the diffuse field is, in the two-stream (Eddington) diffusion approximation of a horizontal
// layer, I(z, μ) = I0(z) + μ·I1(z) with μ the cosine of the propagation direction to the zenith:
//   I0 = skyBelow + (skyAbove − skyBelow)·(τbelow + z0)/(τabove + τbelow + 2·z0),
//   I1 = −(1/(1 − g))·dI0/dτ,   z0 = 2/(3(1 − g)) the extrapolation length (Marshak's boundary
// condition), τabove and τbelow the vertical optical depths of the cloud above and below the
// point. The light the point scatters toward the camera (view direction `dir`, propagation −dir)
// is the phase function's average of I, I0 − g·dir.y·I1, whose share of skyAbove is
//   a = (τbelow + z0·(1 + (3/2)·g·dir.y)) / (τabove + τbelow + 2·z0),  clamped to [0, 1].
// Without cloud around (τ → 0) this is the share of the phase lobe that comes from above,
// ½ + ¾·g·dir.y (first order in the phase function); deep inside it tends to the diffusion
// profile; at the base of a thick layer seen from below (the mean scattering point at optical
// depth dir.y above the base) it equals the Eddington emergent radiance I0 + dir.y·|I1| at the
// base. dir.y: the view direction's cosine to the zenith (> 0 looking up); g: the mean cosine of
// the later phase function; τabove, τbelow dimensionless. Returns a (dimensionless).
CLOUDLUT_FN float skyAboveShare(float tauAbove, float tauBelow, float g, float dirUp) {
  float z0 = 2.0f / (3.0f * max(1.0f - g, 1e-3f));
  float above = max(tauAbove, 0.0f), below = max(tauBelow, 0.0f);
  return clamp((below + z0 * (1.0f + 1.5f * g * dirUp)) / (above + below + 2.0f * z0), 0.0f, 1.0f);
}

// Ambient radiance (the sky's units: radiance per channel) of a chord of optical depth τ under
// that sky: the chord's opacity 1 − e^{−τ} times the field it scatters toward the camera,
// skyBelow + (skyAbove − skyBelow)·a (skyAboveShare at the chord's mean scattering point).
// With skyAbove = skyBelow it is uniformSkyAmbient(τ)·sky exactly, whatever a.
CLOUDLUT_FN vec3 layeredSkyAmbient(float tau, float share, vec3 skyAbove, vec3 skyBelow) {
  return chordOpacity(tau) * (skyBelow + (skyAbove - skyBelow) * share);
}

// Transmittance of the sunlight's scattered part through τ of neighbouring cloud: the
// two-stream (Eddington) transmittance 1/(1 + ¾(1 − g)τ) of a conservative slab of optical
// thickness τ for phase asymmetry g (the mean cosine of the later phase function). It
// lights the particle's multiple scattering where the direct beam e^{−τ} is lower.
CLOUDLUT_FN float diffuseTransmittance(float tau, float g) {
  return 1.0f / (1.0f + 0.75f * (1.0f - g) * max(tau, 0.0f));
}

// The sunlight that lights multiple scattering behind τ of cloud (dimensionless): the larger of
// the direct beam e^{−τ} and the diffuse transmittance T_d(τ) (diffuseTransmittance).
CLOUDLUT_FN float directOrDiffuseTransmittance(float tau, float g) {
  return max(exp(-max(tau, 0.0f)), diffuseTransmittance(tau, g));
}

// Distance (unit-sphere units) from a point x of the unit sphere to its surface along the unit
// direction d: the larger root of |x + t·d| = 1; 0 for a point outside that has passed it.
CLOUDLUT_FN float unitSphereExitDistance(vec3 x, vec3 d) {
  float b = dot(x, d), c = dot(x, x) - 1.0f;
  return max(-b + sqrt(max(b * b - c, 0.0f)), 0.0f);
}

// The share (dimensionless, [0, 1]) of a chord's optical depth that lies within the first share
// u of the span from its first matter toward its last (the optical-depth table's channels 1 and
// 2; u clamped to [0, 1]), the span cut in thirds that each hold their matter evenly, each outer
// third a share `outerThird` of it and the middle one the rest: piecewise linear, slope
// 3a, 3(1 − 2a), 3a over the thirds (a = outerThird, the table's chord_outer_third_share,
// bake/ChordMatterProfile.h). a = 1/3 lays the matter evenly; the reference particle's metaball
// fall-off puts most of it mid-chord (a ≈ 0.26).
CLOUDLUT_FN float chordMatterShare(float u, float outerThird) {
  float t = clamp(u, 0.0f, 1.0f) * 3.0f;
  return outerThird * (min(t, 1.0f) + max(t - 2.0f, 0.0f)) + (1.0f - 2.0f * outerThird) * clamp(t - 1.0f, 0.0f, 1.0f);
}

// The steps of chordMatterShare's slope d share/du (dimensionless) at the four ends of its
// thirds, u = 0, 1/3, 2/3 and 1, rising from 0 and back to it: 3a, 3(1 − 2a) − 3a, 3a − 3(1 − 2a)
// and −3a (a = outerThird). They sum to 0. The sun volume's splat writes a chord's ramp as these
// steps (sun_volume_build.comp.glsl, addRamp).
CLOUDLUT_FN vec4 chordMatterSlopeSteps(float outerThird) {
  float a = outerThird;
  return vec4(3.0f * a, 3.0f * (1.0f - 3.0f * a), -3.0f * (1.0f - 3.0f * a), -3.0f * a);
}

// A particle's own optical depth toward the sun (dimensionless) at the point a share s of the
// way along its sun chord, counted from the chord's sunward end: the chord's optical depth
// tauChord laid from its first matter to its last matter (shares of the chord, the
// optical-depth table's channels 1 and 2) as chordMatterShare lays it, with the table's share
// outerThird in each outer third, as the sun volume does (sunVolumeRampAt).
CLOUDLUT_FN float ownSunRamp(float tauChord, float firstMatter, float lastMatter, float s, float outerThird) {
  return tauChord * chordMatterShare((s - firstMatter) / max(lastMatter - firstMatter, 1e-6f), outerThird);
}

// The same for the multiple table's homogeneous sphere (density ρT̄, the view chord's mean
// density; optical radius σ·ρT̄) in place of the particle, from the point x of the unit sphere
// (particle space) to the sphere's surface along l, toward the sun (unit): ρT̄·σ·distance.
CLOUDLUT_FN float homogeneousOwnSunDepth(vec3 x, vec3 l, float rhoChord, float sigma) {
  return rhoChord * sigma * unitSphereExitDistance(x, l);
}

// The particle's own core shadow on its multiple term (dimensionless, in (0, maxFactor];
// docs/LIGHTING.md, "The particle's own core shadow"). The own term reads the homogeneous sphere
// of the chord's mean density, which at the chord's mean scattering point x̄ lies under
// tauHomogeneous of its own matter toward the sun (homogeneousOwnSunDepth); the particle itself
// lies under tauOwn there (ownSunRamp, the sun volume's own ramp). Where the particle's core
// shadows x̄ more than the sphere would (the far rim of a particle seen toward the sun), the
// term is darkened by the ratio of the sunlight through the two (directOrDiffuseTransmittance,
// as for the neighbours' shadow). Where it lies under less (the band inside the rim toward the
// sun), the term is brightened by the same ratio, but by at most maxFactor (≥ 1; the closure's
// own_core_shadow_max): the ratio's sunlight at one point says less about a whole chord the more
// it departs from 1, and a larger bound over-lights the dense particle's sunlit face, where x̄
// lies past the noise particle's empty outskirts that the sphere fills (docs/LIGHTING.md).
CLOUDLUT_FN float ownCoreShadow(float tauOwn, float tauHomogeneous, float g, float maxFactor) {
  return min(directOrDiffuseTransmittance(tauOwn, g) / directOrDiffuseTransmittance(tauHomogeneous, g),
             maxFactor);
}

// The share of the sun's irradiance (dimensionless) that gets through τ of cloud toward the
// sun, direct and scattered together: the Eddington total transmittance of a conservative slab
// of optical thickness τ lit at normal incidence (the slab's normal taken along the sun),
//   T = (5/4 − ¼ e^{−τ}) / (1 + ¾(1 − g)τ),
// 1 for τ = 0 (capped at 1: the approximation overshoots by < 0.1% for a thin cloud) and
// ≈ (5/3)/((1 − g)τ) for a thick cloud. It lights the ground in the clouds'
// shadow.
CLOUDLUT_FN float slabTransmittance(float tau, float g) {
  float t = max(tau, 0.0f);
  return min(1.0f, (1.25f - 0.25f * exp(-t)) / (1.0f + 0.75f * (1.0f - g) * t));
}

// The cloud around a point as one homogeneous sphere (cloud scale): its diameter along the sun
// is the optical depth of the sun-parallel column through the point, tauColumn = tauSun +
// tauAway (toward the sun and away from it). Its density scale (dimensionless), for unit
// optical radius sigma: tauColumn / (2σ).
CLOUDLUT_FN float cloudSphereDensity(float tauColumn, float sigma) { return tauColumn / (2.0f * sigma); }

// The point on that sphere where the column splits it (cos θS = (tauAway − tauSun)/tauColumn:
// the sub-solar point when no cloud lies toward the sun, the anti-solar point when none lies
// behind), on the great circle through the sun and the camera, on the camera's side, so that the
// view ray `dir` enters the sphere there. Where that point faces away from the camera (a view
// toward the sun at a point with little cloud toward it), the circle's nearest point that faces
// the camera at least slightly (cos 88.85° = 0.02) stands in: the angle from the sun is clamped
// to within 88.85° of the camera's, so the point moves continuously with θS along the limb. (An
// earlier push toward the camera sent the point through the sphere's centre near the sun.)
// Unit vector, world space; the scattering tables depend only on its angles to `dir` and `sun`.
CLOUDLUT_FN vec3 cloudSphereEntry(float tauSun, float tauColumn, vec3 dir, vec3 sun) {
  const float kLimb = 1.55079637f;  // acos(0.02), radians
  float cosS = clamp((tauColumn - 2.0f * tauSun) / max(tauColumn, 1e-6f), -1.0f, 1.0f);
  vec3 toCamera = -dir;
  vec3 t = toCamera - dot(toCamera, sun) * sun;
  if (dot(t, t) < 1e-8f) t = cross(sun, abs(sun.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f));
  t = normalize(t);
  float cameraAngle = azimuth(dot(toCamera, t), dot(toCamera, sun));  // [0, π] from the sun
  float angle = clamp(acos(cosS), cameraAngle - kLimb, cameraAngle + kLimb);
  return cos(angle) * sun + sin(angle) * t;
}

// The local cloud along the sun column through a point: the matter within a window of the
// column, from `window` toward the sun to `window` away from it (a cloud's size, the layer's
// depth), stands for the cloud the point is in; the matter beyond the window's sunward end
// (other clouds, across clear air, that light cannot diffuse through) only shadows it. From the
// optical depths toward the sun (all dimensionless) at the point (tauSun), at the window's
// sunward end (tauSunEnd) and at its far end (tauFarEnd):
//   x  the local cloud toward the sun, tauSun − tauSunEnd;
//   y  the local column, tauFarEnd − tauSunEnd (at least x);
//   z  the optical depth beyond the window toward the sun, tauSunEnd.
// Optical depth grows away from the sun, so tauSunEnd ≤ tauSun ≤ tauFarEnd; values out of that
// order (trilinear reads in different cascades) are clamped into it.
CLOUDLUT_FN vec3 localCloudColumn(float tauSun, float tauSunEnd, float tauFarEnd) {
  float beyond = clamp(tauSunEnd, 0.0f, max(tauSun, 0.0f));
  float toward = max(tauSun, 0.0f) - beyond;
  return vec3(toward, max(tauFarEnd - beyond, toward), beyond);
}

// Weight of the cloud-scale sphere against the particle's own (dimensionless, [0, 1]): the
// share of the column's optical depth that lies outside the particle (columnOutside of
// tauColumn), 0 for a particle alone, → 1 deep in a cloud.
CLOUDLUT_FN float cloudScaleWeight(float columnOutside, float tauColumn) {
  return tauColumn > 0.0f ? clamp(columnOutside / tauColumn, 0.0f, 1.0f) : 0.0f;
}

// The multiple table's angular closure K(ρ, μ) (FORMAT.md, `angular_closure`; docs/LIGHTING.md):
// values on `nodes` density scales log2 ρ = log2RhoFirst + i·log2RhoStep and `bins` uniform bins
// of μ = ω_out·l over [−1, 1], stored node by node (index i·bins + j). K is linear in log2 ρ
// between the nodes and in μ between the bins' centres, and held beyond the first and last.
// These three functions are that interpolation; the caller fetches the four values.

// The continuous grid position (s, m) of density scale ρ (dimensionless) and exit cosine μ,
// clamped to the grid: s in [0, nodes − 1], m in [0, bins − 1].
CLOUDLUT_FN vec2 angularClosurePosition(float rho, float mu, float log2RhoFirst, float log2RhoStep, float nodes,
                                        float bins) {
  float s = clamp((log2(max(rho, 1e-30f)) - log2RhoFirst) / log2RhoStep, 0.0f, nodes - 1.0f);
  float m = clamp((mu + 1.0f) * 0.5f * bins - 0.5f, 0.0f, bins - 1.0f);
  return vec2(s, m);
}

// The cell around grid position p: its first node and bin (s0, m0), as whole numbers, such that
// s0 + 1 and m0 + 1 are in the grid too (when the grid has two of them).
CLOUDLUT_FN vec2 angularClosureCell(vec2 p, float nodes, float bins) {
  return vec2(min(floor(p.x), max(nodes - 2.0f, 0.0f)), min(floor(p.y), max(bins - 2.0f, 0.0f)));
}

// Bilinear K in the cell: k = (K(s0, m0), K(s0, m1), K(s1, m0), K(s1, m1)), m1 = min(m0 + 1,
// bins − 1), s1 likewise; p the grid position, cell its angularClosureCell.
CLOUDLUT_FN float angularClosureBlend(vec4 k, vec2 p, vec2 cell) {
  vec2 f = p - cell;
  return mix(mix(k.x, k.y, f.y), mix(k.z, k.w, f.y), f.x);
}

// ---- Diffusion of the multiply scattered light (render/DiffusionVolume.h, docs/LIGHTING.md) ----
// Where particles make a cloud, the multiply scattered light is the solution of the
// flux-limited diffusion equation −∇·(D∇φ) = q on a grid over the cloud: φ the fluence per unit
// sun irradiance (dimensionless), q what the sun's δ-Eddington-scaled beam loses per unit length
// (1/length), D the diffusion coefficient (length). The functions below are its terms.

// δ-Eddington: the share f = g² of the phase function's forward peak taken as unscattered, for
// the later phase function's mean cosine g (dimensionless); the scaled extinction is (1 − f)·σ.
CLOUDLUT_FN float deltaEddingtonForwardShare(float g) { return g * g; }

// δ-Eddington: the mean cosine g* = (g − f)/(1 − f) = g/(1 + g) of what is left once the forward
// peak f = g² is removed (dimensionless).
CLOUDLUT_FN float deltaEddingtonAsymmetry(float g) { return g / (1.0f + g); }

// Wilson's flux-limited diffusion coefficient D = 1/(3·σtr + |∇φ|/φ) (length): σtr = σ*(1 − g*)
// the transport coefficient (1/length), gradientRatio = |∇φ|/φ (1/length). Deep in a cloud it is
// the classical 1/(3σtr); in clear air it keeps the flux |D∇φ| at most φ, as light can carry.
CLOUDLUT_FN float diffusionCoefficient(float transport, float gradientRatio) {
  return 1.0f / (3.0f * transport + max(gradientRatio, 0.0f));
}

// Marshak's vacuum condition at a grid face h/2 beyond the last node (h its spacing, D the node's
// coefficient, both lengths): the flux that leaves per unit area per unit φ at the node,
// 2D/(4D + h) (dimensionless). From D·(φ − φ_face)/(h/2) = φ_face/2, the flux out = φ_face/2.
CLOUDLUT_FN float marshakExitCoefficient(float D, float h) { return 2.0f * D / (4.0f * D + h); }

// Radiance per unit sun irradiance (1/sr) that a diffuse field of fluence φ and flux J scatters
// toward direction ω, for a phase function of mean cosine g, to first order (P1):
// (φ + 3g·J·ω)/(4π). A chord of optical depth τ sends (1 − e^{−τ}) times it.
CLOUDLUT_FN float diffusedRadiance(float phi, vec3 flux, vec3 omega, float g) {
  return max(phi + 3.0f * g * dot(flux, omega), 0.0f) * 0.0795774715459477f;
}

// Weight of the cloud beside a point (dimensionless, [0, 1]), from the local cloud columns
// (localCloudColumn's y, dimensionless optical depths) through four points around it across the
// sun (besideColumns) and through the point itself (column): the mean of each beside column
// against the point's own (floored at 0.01), each at most 1. 0 with clear air all around the
// point, → 1 inside a cloud. cloudScaleWeight reads the column through the point only, so a
// particle at the side of a heap counts there as alone though the heap beside it diffuses light
// into it.
CLOUDLUT_FN float cloudBesideWeight(vec4 besideColumns, float column) {
  vec4 r = clamp(besideColumns / max(column, 0.01f), 0.0f, 1.0f);
  return 0.25f * (r.x + r.y + r.z + r.w);
}

// Share of a fragment's multiple light taken from the diffusion field rather than the tables
// (dimensionless): `share` (the renderer's setting) where the particle lies deep in a cloud
// (cloudWeight → 1: the larger of cloudScaleWeight and cloudBesideWeight), half of it where it
// stands alone (cloudWeight = 0: the tables hold an isolated particle, a dense one better than
// the grid does), and fading as
// (1 − μ)² with μ = max(v·l, 0) toward the sun: diffusion's P1 field has no forward peak, which
// makes the light seen toward the sun (the backlit rim). Measured against the path tracer,
// docs/LIGHTING.md ("Diffusion of the multiply scattered light").
CLOUDLUT_FN float diffusionShareOfMultiple(float share, float cloudWeight, float viewDotSun) {
  float mu = clamp(viewDotSun, 0.0f, 1.0f);
  return share * (0.5f + 0.5f * clamp(cloudWeight, 0.0f, 1.0f)) * (1.0f - mu) * (1.0f - mu);
}
