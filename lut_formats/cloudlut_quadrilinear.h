// cloudlut_quadrilinear.h — quadrilinear interpolation of a 4D cloudlut table held as floats.
//
// C++17, standard library only. The one CPU definition of the interpolation the shaders get
// from cloudlut_sampling.glsl (hardware trilinear over axes 0-2, linear across axis 3): the
// engine reader (cloudlut_lut.h) and cloudlut's own Table4D both call it.
//
// Layout (lut_formats/FORMAT.md section 1): axis 0 fastest, then 1, 2, 3; `channels` values
// interleaved per node. Node i of an axis of n nodes sits at the axis fraction i / (n - 1).
#ifndef CLOUDLUT_QUADRILINEAR_H
#define CLOUDLUT_QUADRILINEAR_H

#include <algorithm>
#include <cstddef>
#include <cstdint>

namespace cloudlut_reader {

// Index of node (i0, i1, i2, i3) of a table of dimensions dims (axis 0 fastest); multiply by
// the channel count for the node's first value.
inline std::size_t nodeIndex(const std::uint32_t dims[4], std::uint32_t i0, std::uint32_t i1,
                             std::uint32_t i2, std::uint32_t i3) {
  return ((static_cast<std::size_t>(i3) * dims[2] + i2) * dims[1] + i1) * dims[0] + i0;
}

// The cell of an axis of n nodes that holds the axis fraction x (clamped to [0, 1]): node
// position p = x·(n − 1), lower node i = min(⌊p⌋, n − 2) and fraction f = p − i ∈ [0, 1]
// (i = 0, f = 0 on an axis of one node).
inline void locateCell(float x, std::uint32_t n, std::uint32_t& i, float& f) {
  const float p = std::min(std::max(x, 0.0f), 1.0f) * static_cast<float>(n - 1);
  i = std::min(static_cast<std::uint32_t>(p), n >= 2 ? n - 2 : 0u);
  f = n > 1 ? p - static_cast<float>(i) : 0.0f;
}

// out[c] = Σ over the 16 corners j ∈ {i, i+1}⁴ of Π_k (j_k = i_k + 1 ? f_k : 1 − f_k) · value(j, c),
// for the cell with lower nodes i and fractions f (an axis of one node contributes its node
// with weight 1). Writes `channels` values to out.
inline void interpolateCell(const float* values, const std::uint32_t dims[4], std::size_t channels,
                            const std::uint32_t i[4], const float f[4], float* out) {
  for (std::size_t c = 0; c < channels; ++c) out[c] = 0.0f;
  for (int corner = 0; corner < 16; ++corner) {
    float w = 1.0f;
    std::uint32_t j[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; ++k) {
      const bool hi = ((corner >> k) & 1) != 0;
      if (hi && dims[k] < 2) {
        w = 0.0f;
        break;
      }
      j[k] = i[k] + (hi ? 1u : 0u);
      w *= hi ? f[k] : 1.0f - f[k];
    }
    if (w == 0.0f) continue;
    const float* node = values + nodeIndex(dims, j[0], j[1], j[2], j[3]) * channels;
    for (std::size_t c = 0; c < channels; ++c) out[c] += w * node[c];
  }
}

// Quadrilinear interpolation of the table at axis fractions x ∈ [0, 1]⁴ (clamped): the cell
// of each axis by locateCell, then interpolateCell. Writes `channels` values to out.
inline void sampleQuadrilinear(const float* values, const std::uint32_t dims[4], std::size_t channels,
                               const float x[4], float* out) {
  std::uint32_t i[4];
  float f[4];
  for (int k = 0; k < 4; ++k) locateCell(x[k], dims[k], i[k], f[k]);
  interpolateCell(values, dims, channels, i, f, out);
}

}  // namespace cloudlut_reader

#endif  // CLOUDLUT_QUADRILINEAR_H
