// volume_pieces.glsl — what both resolves of volume-aware blending share (seed §5.5, eqs. 15–17):
// a segment's extinction and source, the total order of segments, and one piece of the sweep.
// Preceded by volume_fragments.glsl (the node pool).
//
// A segment from entry a to exit b (world units) with optical depth τ and radiance R (what the
// particle pass stored, premultiplied) has extinction κ = τ/(b − a) (per world unit) and colour
// C = R/(1 − e^{−τ}), so κ·C = (τ/(b − a))·R/(1 − e^{−τ}). Inside a piece of length d where the
// segments present add their extinctions and their sources weighted by extinction (eq. 15), the
// piece scatters (Σκ_i C_i/Σκ_i)(1 − e^{−Σκ_i d}) and passes e^{−Σκ_i d}; the pieces are composited
// front to back (eqs. 16–17).

// τ / (1 − e^{−τ}), stable at τ → 0.
float opacityRatio(float tau) { return tau < 1e-4f ? 1.0f + 0.5f * tau : tau / (1.0f - exp(-tau)); }
// (1 − e^{−x}) / x, stable at x → 0.
float expRatio(float x) { return x < 1e-4f ? 1.0f - 0.5f * x : (1.0f - exp(-x)) / x; }

// The total order of segments: −1, 0 or +1 as segment (aA, node nA) comes before, ties with or
// comes after (aB, nB). By entry distance a (world units), then the words of the nodes (exit, τ,
// radiance) as unsigned integers: nodes that tie hold the same segment, so which of them is taken
// first changes nothing.
int compareKeys(float aA, uint nA, float aB, uint nB) {
  if (aA != aB) return aA < aB ? -1 : 1;
  if (nA == nB) return 0;
  for (uint w = 1u; w < 6u; ++w) {
    uint x = fragmentWord(nA, w);
    uint y = fragmentWord(nB, w);
    if (x != y) return x < y ? -1 : 1;
  }
  return 0;
}

// A node's entry a (world units along the view ray).
float segmentEntry(uint node) { return uintBitsToFloat(fragmentWord(node, 0u)); }
// Its exit b, kept a little past its entry a, so that κ is finite.
float segmentExit(uint node, float a) {
  return max(uintBitsToFloat(fragmentWord(node, 1u)), a + max(1e-6f * abs(a), 1e-9f));
}
// Its exit b, κ and κ·C.
void segmentTerms(uint node, float a, out float b, out float kappa, out vec3 kappaColor) {
  vec3 span = fragmentSpan(node);
  b = segmentExit(node, a);
  float len = b - a;
  kappa = span.z / len;
  kappaColor = fragmentRadiance(node) * (opacityRatio(span.z) / len);
}

// Adds a piece of length d (world units) with total extinction `kappa` and total source
// `kappaColor` (Σκ_i C_i) behind the transmittance so far, and takes its transmittance in.
void addPiece(inout vec3 color, inout float transmittance, float kappa, vec3 kappaColor, float d) {
  float x = max(kappa, 0.0f) * d;
  color += transmittance * max(kappaColor, vec3(0.0f)) * d * expRatio(x);  // (Σκc/κ)(1 − e^{−κd})
  transmittance *= exp(-x);
}
