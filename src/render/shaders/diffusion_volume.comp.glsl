// diffusion_volume.comp.glsl — the multiply scattered light of a cloud as flux-limited diffusion
// (render/DiffusionVolume.h, docs/LIGHTING.md "Diffusion of the multiply scattered light"), solved
// on the nodes of a vertical column volume (render/SunVolume built toward +y: a node holds τ, the
// optical depth of the cloud above it) and lit through the sun volume. Preceded by the files of
// sun_volume_sampling.glsl (sunOpticalDepth) and cloudlut_shading.glsl (the diffusion functions).
// All lengths in world units; φ is the fluence per unit sun irradiance (dimensionless: W/m² of
// fluence per W/m² of irradiance), q its source per world unit.
//   STAGE 0  per node: σ* (δ-Eddington scaled extinction) and q, the scaled beam's loss across
//            the node's cell; the field starts at φ = 0 with D = 1/(3σ*(1 − g*) + 1/h), or, in a
//            warm start (uKeepField), keeps the last solve's φ and D over the same nodes.
//   STAGE 1  half a sweep (the nodes of one colour, red-black; one lane per node of that colour) of
//            successive over-relaxation of
//            −∇·(D∇φ) = q (7-point, harmonic mean of D across each face, Marshak's vacuum
//            condition on the grid's faces, marshakExitCoefficient), in place; D from the field
//            by Wilson's flux limiter (diffusionCoefficient).
//   STAGE 2  φ and the flux J = −D∇φ (world axes) for the particle shader.
//   STAGE 3  one level coarser (coarse node I at fine node 2I, spacing doubled): σ* and q as the
//            full-weighting average of the fine nodes around, the field started as in STAGE 0.
//   STAGE 4  the coarse level's solution, trilinear, as the start of the finer level's sweeps.
//   STAGE 5  all the sweeps of STAGE 1 on a small level in one work group, a barrier between
//            the half-sweeps: the same updates in the same order, without a dispatch each
//            (llvmpipe pays about 40 µs a dispatch, more than a coarse level's half-sweep).
//   STAGE 6  per node: the residual r = q − (−∇·(D∇φ)) of the level's equation (the discrete
//            operator of STAGE 1 with the stored D) and D into uFlux's first two channels.
//   STAGE 7  one level coarser: the finer level's residual and D (STAGE 6) by full weighting as
//            the coarse level's source and D, its φ started at zero: the coarse level now
//            solves for the correction e, −∇·(D∇e) = r (linear: its sweeps keep D). The finer
//            level's D, not the coarse level's own, makes the two operators agree where the
//            flux limiter sets D (clear air, where it scales with the spacing); with its own,
//            the cycles overshot by turns (docs/LIGHTING.md "Convergence").
//   STAGE 8  the coarse level's correction, trilinear, added to the finer level's φ.
// STAGES 6–8 make the correction cycle of render/DiffusionVolume.cpp (a V-cycle on the finest
// level, D frozen on the coarse ones).
// After the solve, diffusion_beside.comp.glsl weighs the cloud beside the nodes for the particle
// shader's share.
// The solve runs coarse to fine (render/DiffusionVolume.cpp): the coarsest level's sweeps carry
// the light across the cloud, each finer level's only the detail.

#if STAGE == 5
layout(local_size_x = WHOLE_GROUP) in;  // WHOLE_GROUP: render/DiffusionVolume.cpp's kWholeGroup
#else
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;
#endif

uniform sampler3D uColumnTau;  // the vertical volume's τ, one cascade (texel = node)
uniform ivec3 uNodes;          // nodes per grid axis
uniform mat4 uNodeToWorld;     // node (i, j, k) → world point
uniform mat4 uWorldToNode;     // the inverse
uniform vec3 uSpacing;         // world distance between neighbouring nodes along each grid axis
uniform float uLaterAsymmetry; // g of the later phase function
uniform int uColour;            // STAGE 1: the nodes (i + j + k) mod 2 = uColour are updated
uniform float uOverRelaxation;  // STAGE 1: successive over-relaxation factor ω in [1, 2)
uniform int uSweeps;            // STAGE 5: the sweeps (each two half-sweeps)
uniform int uKeepDiffusivity;   // STAGE 1 and 5: 1 keeps each node's D (a correction's sweeps)
uniform int uKeepField;         // STAGE 0: 1 keeps the field as the last solve left it (a warm start)

layout(rg32f, binding = 0) uniform image3D uMedium;  // σ*, q
#if STAGE == 5
layout(rg32f, binding = 1) coherent uniform image3D uField;  // φ, D: read by the group's other invocations
#else
layout(rg32f, binding = 1) uniform image3D uField;   // φ, D
#endif
layout(rg32f, binding = 2) uniform image3D uFineMedium;  // STAGE 3: the finer level's σ*, q
layout(rgba32f, binding = 3) uniform image3D uFlux;   // φ, J (STAGE 2); r and D (STAGE 6 and 7)
uniform ivec3 uFineNodes;       // STAGE 3 and 7: the finer level's nodes
uniform sampler3D uCoarseField; // STAGE 4 and 8: the coarser level's φ (or e), D (texel = node)
uniform ivec3 uCoarseNodes;     // STAGE 4 and 8

// The grid axis of the columns: a column volume's slices are its grid's third axis (SunVolumeGrid).
const int kVerticalAxis = 2;

bool outside(ivec3 n) { return any(lessThan(n, ivec3(0))) || any(greaterThanEqual(n, uNodes)); }

// The field before the sweeps at node n: φ = 0 and D for the scaled extinction σ* (1/length) with
// the steepest gradient the grid resolves, |∇φ|/φ = 1/h (h the least spacing, length).
void startField(ivec3 n, float sigmaStar, float gStar, float hMin) {
  imageStore(uField, n, vec4(0.0, diffusionCoefficient(sigmaStar * (1.0 - gStar), 1.0 / hMin), 0.0, 0.0));
}

#if STAGE == 1 || STAGE == 2 || STAGE == 5 || STAGE == 6
// The 7-point stencil of −∇·(D∇φ) at node n whose field is c = (φ, D) (harmonic mean of D across
// each face, Marshak's vacuum condition on the grid's faces): −∇·(D∇φ) = diagonal·φ − (sum − q),
// so sum = q + the neighbours' φ by their face weights (1/length²); and the central-difference
// gradient of φ per grid axis (1/length).
struct Stencil {
  float diagonal, sum;
  vec3 gradient;
};
Stencil stencilAt(ivec3 n, vec2 c, float source) {
  Stencil st = Stencil(0.0, source, vec3(0.0));
  for (int a = 0; a < 3; ++a) {
    float h = uSpacing[a];
    float phiSide[2];
    for (int s = 0; s < 2; ++s) {
      ivec3 k = n;
      k[a] += 2 * s - 1;
      if (outside(k)) {  // the grid's face: Marshak's condition, flux out = marshakExitCoefficient · φ
        st.diagonal += marshakExitCoefficient(c.y, h) / h;
        phiSide[s] = c.x;
        continue;
      }
      vec2 m = imageLoad(uField, k).xy;
      float face = 2.0 * c.y * m.y / max(c.y + m.y, 1e-30) / (h * h);
      st.diagonal += face;
      st.sum += face * m.x;
      phiSide[s] = m.x;
    }
    st.gradient[a] = (phiSide[1] - phiSide[0]) / (2.0 * h);
  }
  return st;
}
#endif

#if STAGE == 1 || STAGE == 2 || STAGE == 5
// At node n: one red-black over-relaxed update of φ and D (STAGE 1 and 5; D kept with
// uKeepDiffusivity), or φ and the flux J (STAGE 2), from the six neighbours.
void updateNode(ivec3 n, float gStar, float hMin) {
  vec2 medium = imageLoad(uMedium, n).xy;
  vec2 c = imageLoad(uField, n).xy;
  Stencil st = stencilAt(n, c, medium.y);
#if STAGE != 2
  float phi = mix(c.x, st.sum / max(st.diagonal, 1e-30), uOverRelaxation);
  if (uKeepDiffusivity != 0) {
    imageStore(uField, n, vec4(phi, c.y, 0.0, 0.0));
    return;
  }
  float extent = max(float(uNodes.x) * uSpacing.x, max(float(uNodes.y) * uSpacing.y, float(uNodes.z) * uSpacing.z));
  // |∇φ|/φ, between 1/(the grid's extent) and 1/h: a node still dark while its neighbours are lit
  // (the first sweeps) must not take D → 0, and no gradient the grid resolves is steeper
  float ratio = clamp(length(st.gradient) / max(c.x, 1e-30), 1.0 / extent, 1.0 / hMin);
  imageStore(uField, n, vec4(phi, diffusionCoefficient(medium.x * (1.0 - gStar), ratio), 0.0, 0.0));
#else
  // grid axes → world: ∇_world φ = Gᵀ ∇_grid φ, G the world → node map's linear part
  vec3 perNode = st.gradient * uSpacing;
  vec3 world = transpose(mat3(uWorldToNode)) * perNode;
  imageStore(uFlux, n, vec4(c.x, -c.y * world));
#endif
}
#endif

#if STAGE == 3 || STAGE == 7
// At coarse node n (fine node 2n): the full-weighting average of the finer level's pair (STAGE 3
// its σ*, q; STAGE 7 its r, D) over the 27 fine nodes around, weight (2 − |d|) per axis at
// offset d, leaving out those beyond the finer grid.
vec2 fullWeighting(ivec3 n) {
  vec2 sum = vec2(0.0);
  float weights = 0.0;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        ivec3 k = 2 * n + ivec3(dx, dy, dz);
        if (any(lessThan(k, ivec3(0))) || any(greaterThanEqual(k, uFineNodes))) continue;
        float w = float((2 - abs(dx)) * (2 - abs(dy)) * (2 - abs(dz)));
#if STAGE == 3
        sum += w * imageLoad(uFineMedium, k).xy;
#else
        sum += w * imageLoad(uFlux, k).xy;
#endif
        weights += w;
      }
  return sum / max(weights, 1e-30);
}
#endif

// Red-black: a half-sweep's lane (i, j, k), i over half the nodes along x, stands for the node of
// its row whose colour (i + j + k) mod 2 is `colour` (a lane per node of the other colour too
// would run masked and cost the same).
ivec3 colourNode(ivec3 lane, int colour) { return ivec3(2 * lane.x + ((lane.y + lane.z + colour) & 1), lane.yz); }
// The δ-Eddington asymmetry g* (dimensionless) and the smallest node spacing (world units).
float scaledAsymmetry() { return deltaEddingtonAsymmetry(uLaterAsymmetry); }
float smallestSpacing() { return min(uSpacing.x, min(uSpacing.y, uSpacing.z)); }

#if STAGE == 5
// (k / d, k mod d) for 0 ≤ k < 2^24 and d ≥ 1, from a float quotient corrected by one: exact, as
// both are exact floats and the rounded quotient lies within one of the true one. llvmpipe has no
// vector integer division and divides lane by lane, which took about a seventh of a small scene's
// light-space passes in this loop (docs/BENCHMARKS.md).
ivec2 quotientAndRemainder(int k, int d) {
  int q = int(float(k) / float(d));
  int r = k - q * d;
  if (r < 0) {
    q -= 1;
    r += d;
  } else if (r >= d) {
    q += 1;
    r -= d;
  }
  return ivec2(q, r);
}

// One work group: its invocations take the nodes of one colour in turn (every other one along x,
// as STAGE 1's dispatch), then wait for each other before the other colour.
void main() {
  float gStar = scaledAsymmetry();
  float hMin = smallestSpacing();
  int halfX = (uNodes.x + 1) / 2;
  int count = halfX * uNodes.y * uNodes.z;
  for (int i = 0; i < 2 * uSweeps; ++i) {
    int colour = i & 1;
    for (int k = int(gl_LocalInvocationIndex); k < count; k += WHOLE_GROUP) {
      ivec2 row = quotientAndRemainder(k, halfX);             // (y + Ny·z, x / 2)
      ivec2 slice = quotientAndRemainder(row.x, uNodes.y);   // (z, y)
      ivec3 n = colourNode(ivec3(row.y, slice.y, slice.x), colour);
      if (!outside(n)) updateNode(n, gStar, hMin);
    }
    memoryBarrierImage();
    barrier();
  }
}
#else
void main() {
  ivec3 n = ivec3(gl_GlobalInvocationID);
#if STAGE == 1
  n = colourNode(n, uColour);  // the dispatch covers the nodes of colour uColour
#endif
  if (outside(n)) return;
  float f = deltaEddingtonForwardShare(uLaterAsymmetry);
  float gStar = scaledAsymmetry();
  float hMin = smallestSpacing();
#if STAGE == 0
  // σ from the vertical volume: τ falls toward +y by σ per unit length (central difference)
  ivec3 up = n, down = n;
  up[kVerticalAxis] = min(n[kVerticalAxis] + 1, uNodes[kVerticalAxis] - 1);
  down[kVerticalAxis] = max(n[kVerticalAxis] - 1, 0);
  float span = float(up[kVerticalAxis] - down[kVerticalAxis]) * uSpacing[kVerticalAxis];
  float sigma = span > 0.0 ? max(texelFetch(uColumnTau, down, 0).r - texelFetch(uColumnTau, up, 0).r, 0.0) / span : 0.0;
  float sigmaStar = (1.0 - f) * sigma;
  vec3 x = (uNodeToWorld * vec4(vec3(n), 1.0)).xyz;
  float near = (1.0 - f) * sunOpticalDepth(x + 0.5 * hMin * uSunColumns);
  float far = (1.0 - f) * sunOpticalDepth(x - 0.5 * hMin * uSunColumns);
  float q = max(exp(-near) - exp(-far), 0.0) / hMin;
  imageStore(uMedium, n, vec4(sigmaStar, q, 0.0, 0.0));
  if (uKeepField == 0) startField(n, sigmaStar, gStar, hMin);
#elif STAGE == 3
  vec2 medium = fullWeighting(n);
  imageStore(uMedium, n, vec4(medium, 0.0, 0.0));
  startField(n, medium.x, gStar, hMin);
#elif STAGE == 4 || STAGE == 8
  vec3 g = min(vec3(n) * 0.5, vec3(uCoarseNodes) - 1.0);
  vec2 coarse = texture(uCoarseField, (g + 0.5) / vec3(uCoarseNodes)).xy;
#if STAGE == 4
  imageStore(uField, n, vec4(coarse, 0.0, 0.0));
#else
  vec2 c = imageLoad(uField, n).xy;
  imageStore(uField, n, vec4(c.x + coarse.x, c.y, 0.0, 0.0));
#endif
#elif STAGE == 6
  vec2 c = imageLoad(uField, n).xy;
  Stencil st = stencilAt(n, c, imageLoad(uMedium, n).y);
  imageStore(uFlux, n, vec4(st.sum - st.diagonal * c.x, c.y, 0.0, 0.0));
#elif STAGE == 7
  vec2 errorEquation = fullWeighting(n);  // r, D
  imageStore(uMedium, n, vec4(imageLoad(uMedium, n).x, errorEquation.x, 0.0, 0.0));
  imageStore(uField, n, vec4(0.0, errorEquation.y, 0.0, 0.0));
#else
  updateNode(n, gStar, hMin);
#endif
}
#endif
