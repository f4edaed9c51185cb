#pragma once
// One radial node's phase product out = M · in (ScatteringOperator.h, convolvePhase) with eight
// zenith nodes per AVX2 vector, giving exactly Eigen's floats: each output is Eigen's sum of the
// same products in the same order (no fused multiply-add), so the tables do not move.
namespace cloudlut::bake {

// Whether phaseProductAvx2 applies to these sizes on this machine: the AVX2 paths are compiled
// and the processor has them, outDirs and nt are multiples of 4, and Eigen's product would sum
// every output in one depth block (its blocking for this cache; else its order is not ours).
bool phaseProductAvx2Applies(int outDirs, int inDirs, int nt);

// out (outDirs × nt, row-major) = M · in (in: inDirs × nt, row-major; M(i, k) = Mt[k·outDirs +
// i]). Only where phaseProductAvx2Applies(outDirs, inDirs, nt).
void phaseProductAvx2(const float* Mt, int outDirs, int inDirs, const float* in, int nt, float* out);

}  // namespace cloudlut::bake
