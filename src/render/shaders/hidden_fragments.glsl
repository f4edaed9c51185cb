// hidden_fragments.glsl — the per-pixel state of hidden-fragment culling (render/
// HiddenFragments.h): the farthest exit D (world distance from the eye, as float bits; 0: none)
// of the segments stored so far, and their summed optical depth τ_front (fixed point, units of
// 1/FRONT_TAU_UNIT). Preceded by HiddenFragments::defines(): HIDDEN_OPTICAL_DEPTH (−ln of
// kHiddenTransmittance), FRONT_TAU_UNIT.

layout(r32ui, binding = 2) uniform coherent uimage2D uFrontExit;
layout(r32ui, binding = 3) uniform coherent uimage2D uFrontTau;

// The distance beyond which a fragment of pixel `px` is hidden (world units; +∞ while the
// segments stored so far let through more than kHiddenTransmittance). Reads τ_front before D:
// every segment counted in the sum has already raised D.
float hiddenBeyond(ivec2 px) {
  float frontTau = float(imageLoad(uFrontTau, px).x) / FRONT_TAU_UNIT;
  memoryBarrierImage();
  float frontExit = uintBitsToFloat(imageLoad(uFrontExit, px).x);
  return frontTau >= HIDDEN_OPTICAL_DEPTH ? frontExit : uintBitsToFloat(0x7f800000u);
}

// Counts a stored segment that exits at `exitDistance` (world units) with optical depth `tau`:
// D first, then the sum (τ rounded down, at most 64 per segment so that the sum cannot wrap).
void addFrontSegment(ivec2 px, float exitDistance, float tau) {
  imageAtomicMax(uFrontExit, px, floatBitsToUint(max(exitDistance, 0.0)));
  memoryBarrierImage();
  imageAtomicAdd(uFrontTau, px, uint(clamp(tau, 0.0, 64.0) * FRONT_TAU_UNIT));
}
