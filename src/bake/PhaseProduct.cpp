#include "bake/PhaseProduct.h"

#include <cstring>

#include <Eigen/Core>

#include "core/Float4.h"

namespace cloudlut::bake {

// Eigen's order, which these kernels reproduce: `o.noalias() = m * a` with o and a row-major
// runs as the column-major product o^T = a^T · m^T, whose rows are the nt zenith nodes. Eigen
// (SSE, no FMA) sums rows in groups of 8 over k = 0, 1, …, inDirs − 1 in turn, starting from 0;
// a last group of 4 rows sums even k and odd k apart up to inDirs rounded down to 8, adds the
// two, then adds the remaining k in turn. The result is 0 + 1·sum, which equals the sum.
#if CLOUDLUT_AVX2_LANES
namespace {

constexpr int kPeel = 8;  // Eigen's depth peeling

// Zenith columns j0 … j0 + 8·B − 1 of rows i0 … i0 + 3: sums over k in turn.
template <int B>
[[gnu::always_inline]] inline void sequentialColumns(const float* Mt, int outDirs, int inDirs, const float* in, int nt,
                                                     int i0, int j0, float* out) {
  Float8 acc[4][B] = {};
  for (int k = 0; k < inDirs; ++k) {
    Float8 x[B];
    for (int b = 0; b < B; ++b) std::memcpy(&x[b], in + static_cast<std::size_t>(k) * nt + j0 + 8 * b, sizeof x[b]);
    const float* m = Mt + static_cast<std::size_t>(k) * outDirs + i0;
    for (int r = 0; r < 4; ++r)
      for (int b = 0; b < B; ++b) acc[r][b] = acc[r][b] + x[b] * m[r];
  }
  for (int r = 0; r < 4; ++r)
    for (int b = 0; b < B; ++b)
      std::memcpy(out + static_cast<std::size_t>(i0 + r) * nt + j0 + 8 * b, &acc[r][b], sizeof acc[r][b]);
}

// The last four zenith columns (j0 = nt − 4) of rows i0 … i0 + 3: even and odd k apart, then
// the rest in turn.
[[gnu::always_inline]] inline void pairedColumns(const float* Mt, int outDirs, int inDirs, const float* in, int nt,
                                                 int i0, int j0, float* out) {
  Float4 even[4] = {}, odd[4] = {};
  const int peeled = inDirs / kPeel * kPeel;
  for (int k = 0; k < peeled; k += 2) {
    const Float4 x0 = loadFloat4(in + static_cast<std::size_t>(k) * nt + j0);
    const Float4 x1 = loadFloat4(in + static_cast<std::size_t>(k + 1) * nt + j0);
    const float* m0 = Mt + static_cast<std::size_t>(k) * outDirs + i0;
    const float* m1 = m0 + outDirs;
    for (int r = 0; r < 4; ++r) {
      even[r] = even[r] + x0 * m0[r];
      odd[r] = odd[r] + x1 * m1[r];
    }
  }
  for (int r = 0; r < 4; ++r) even[r] = even[r] + odd[r];
  for (int k = peeled; k < inDirs; ++k) {
    const Float4 x = loadFloat4(in + static_cast<std::size_t>(k) * nt + j0);
    const float* m = Mt + static_cast<std::size_t>(k) * outDirs + i0;
    for (int r = 0; r < 4; ++r) even[r] = even[r] + x * m[r];
  }
  for (int r = 0; r < 4; ++r) std::memcpy(out + static_cast<std::size_t>(i0 + r) * nt + j0, &even[r], sizeof even[r]);
}

}  // namespace
#endif

bool phaseProductAvx2Applies(int outDirs, int inDirs, int nt) {
  if (!cpuHasAvx2Lanes() || outDirs % 4 != 0 || nt % 4 != 0) return false;
  // Eigen's blocking for this product (column-major o^T = a^T · m^T: nt rows, inDirs deep).
  Eigen::Index kc = inDirs, mc = nt, nc = outDirs;
  Eigen::internal::computeProductBlockingSizes<float, float, 1>(kc, mc, nc, Eigen::Index{1});
  return kc >= inDirs && (mc >= nt || mc % 8 == 0);
}

#if CLOUDLUT_AVX2_LANES
__attribute__((target("avx2"))) void phaseProductAvx2(const float* Mt, int outDirs, int inDirs, const float* in,
                                                      int nt, float* out) {
  const int wide = nt / 8 * 8;  // zenith columns in Eigen's groups of 8
  for (int i0 = 0; i0 < outDirs; i0 += 4) {
    int j0 = 0;
    for (; j0 + 16 <= wide; j0 += 16) sequentialColumns<2>(Mt, outDirs, inDirs, in, nt, i0, j0, out);
    if (j0 < wide) sequentialColumns<1>(Mt, outDirs, inDirs, in, nt, i0, j0, out);
    if (wide < nt) pairedColumns(Mt, outDirs, inDirs, in, nt, i0, wide, out);
  }
}
#else
// Never called: phaseProductAvx2Applies is false where the AVX2 paths are not compiled.
void phaseProductAvx2(const float*, int, int, const float*, int, float*) {}
#endif

}  // namespace cloudlut::bake
