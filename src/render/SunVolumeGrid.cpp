#include "render/SunVolumeGrid.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace cloudlut::render {

namespace {

// Row 2 (w) of a cascade's map m (m[column][row]) and its homogeneous row: w = (x_a − h0)/dh
// when the sun lies toward +a (sunPositive), (h1 − x_a)/dh otherwise, so that w grows toward the
// sun; world units in, slices out.
void setSliceRow(glm::mat4& m, int a, bool sunPositive, float h0, float h1, float dh) {
  m[a][2] = (sunPositive ? 1.0f : -1.0f) / dh;
  m[3][2] = (sunPositive ? -h0 : h1) / dh;
  m[3][3] = 1.0f;
}

// The affine map of one cascade. Axis a holds the slices, axes b and c the columns; the sheared
// column coordinates are p = x_b − (x_a − h0)·l_b/l_a and q = x_c − (x_a − h0)·l_c/l_a, so a
// line of constant (p, q) runs along l. u = (p − p0)/du, v = (q − q0)/du, and w = (x_a − h0)/dh
// when the sun lies toward +a, (h1 − x_a)/dh otherwise (w grows toward the sun).
glm::mat4 gridMap(int a, const glm::vec3& l, float h0, float h1, float p0, float q0, float du, float dh) {
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const float sb = l[b] / l[a], sc = l[c] / l[a];
  glm::mat4 m(0.0f);  // m[column][row]
  // row 0: u
  m[b][0] = 1.0f / du;
  m[a][0] = -sb / du;
  m[3][0] = (sb * h0 - p0) / du;
  // row 1: v
  m[c][1] = 1.0f / du;
  m[a][1] = -sc / du;
  m[3][1] = (sc * h0 - q0) / du;
  setSliceRow(m, a, l[a] > 0.0f, h0, h1, dh);
  return m;
}

// Where the sun ray (unit l, l.y ≠ 0) through x crosses the plane y = y0: its (x, z), world units.
glm::vec2 layerIntercept(const glm::vec3& x, const glm::vec3& l, float y0) {
  const float s = (y0 - x.y) / l.y;
  return glm::vec2(x.x + s * l.x, x.z + s * l.z);
}

// The affine map of one cascade over a horizontal layer [h0, h1]: slices along y, columns indexed
// by where their sun ray crosses y = h0, in a frame turned to the sun's azimuth h (unit, in the
// x–z plane): along = (intercept · h − o.x)/(du/|l_y|), across = (intercept · h⊥ − o.y)/du, with
// h⊥ = (−h_z, h_x). Two sun rays whose intercepts are d apart along h are d·|l_y| apart across
// the beam, so the columns stretched by 1/|l_y| (`stretch`) along h are du apart across the beam
// in both directions: a particle's shadow covers about π(r/du)² columns whatever the sun's
// elevation (a square grid on the plane would need 1/|l_y| times as many for a low sun). h is
// the sun's azimuth, so the intercept's h⊥ component does not change with y. w as in gridMap.
glm::mat4 layerGridMap(const glm::vec3& l, const glm::vec2& h, float stretch, float h0, float h1, const glm::vec2& o,
                       float du, float dh) {
  const float duAlong = du * stretch;
  const float slopeAlong = (h.x * l.x + h.y * l.z) / l.y;  // d(intercept · h)/dy = −slopeAlong
  glm::mat4 m(0.0f);  // m[column][row]; world x, y, z are columns 0, 1, 2
  m[0][0] = h.x / duAlong;
  m[2][0] = h.y / duAlong;
  m[1][0] = -slopeAlong / duAlong;
  m[3][0] = (slopeAlong * h0 - o.x) / duAlong;
  m[0][1] = -h.y / du;
  m[2][1] = h.x / du;
  m[3][1] = -o.y / du;
  setSliceRow(m, 1, l.y > 0.0f, h0, h1, dh);
  return m;
}

void setCascade(SunVolumeGrid& g, int k, const glm::mat4& toGrid) {
  g.toGrid[k] = toGrid;
  g.toWorld[k] = glm::inverse(toGrid);
}

}  // namespace

SunVolumeGrid sunVolumeGridForBounds(const glm::vec3& lo, const glm::vec3& hi, const glm::vec3& sunIn, float spacing,
                                     int maxColumns, int maxSlices) {
  const glm::vec3 l = glm::normalize(sunIn);
  int a = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(l[i]) > std::abs(l[a])) a = i;
  const int b = (a + 1) % 3, c = (a + 2) % 3;
  const float h0 = lo[a], h1 = hi[a];
  // Sheared bounds of the box: its eight corners.
  float pLo = INFINITY, pHi = -INFINITY, qLo = INFINITY, qHi = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 x((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    const float p = x[b] - (x[a] - h0) * l[b] / l[a], q = x[c] - (x[a] - h0) * l[c] / l[a];
    pLo = std::min(pLo, p);
    pHi = std::max(pHi, p);
    qLo = std::min(qLo, q);
    qHi = std::max(qHi, q);
  }
  const float extent = std::max(pHi - pLo, qHi - qLo);
  float du = std::max(spacing, extent / static_cast<float>(maxColumns - 3));
  const float la = std::abs(l[a]);
  float dh = du * la;
  dh = std::max(dh, (h1 - h0) / static_cast<float>(maxSlices));
  if (!(dh > 0.0f)) dh = du;
  SunVolumeGrid g;
  g.cascades = 1;
  g.sliceAxis = a;
  g.sun = l;
  g.localCloud = hi.y - lo.y;
  // One empty column on each side, so that sampling between the last column and the border
  // (GL_CLAMP_TO_BORDER, τ = 0) fades out instead of stopping.
  const int nu = static_cast<int>(std::ceil((pHi - pLo) / du)) + 3;
  const int nv = static_cast<int>(std::ceil((qHi - qLo) / du)) + 3;
  const int nw = static_cast<int>(std::ceil((h1 - h0) / dh)) + 1;
  g.dims = glm::ivec3(std::min(nu, maxColumns), std::min(nv, maxColumns), std::max(std::min(nw, maxSlices + 1), 2));
  setCascade(g, 0, gridMap(a, l, h0, h0 + dh * static_cast<float>(g.dims.z - 1), pLo - du, qLo - du, du, dh));
  return g;
}

SunVolumeGrid sunVolumeGridForLayer(const glm::vec3& eye, float yLo, float yHi, const glm::vec3& sunIn, float spacing0,
                                    int cascades, int columns, int slices, float ratio, float minElevation) {
  glm::vec3 l = glm::normalize(sunIn);
  const float horizontal = glm::length(glm::vec2(l.x, l.z));
  const glm::vec2 h = horizontal > 1e-6f ? glm::vec2(l.x, l.z) / horizontal : glm::vec2(1.0f, 0.0f);
  if (std::abs(l.y) < minElevation) {
    const float y = l.y < 0.0f ? -minElevation : minElevation;
    const float r = std::sqrt(1.0f - y * y);
    l = glm::vec3(h.x * r, y, h.y * r);
  }
  SunVolumeGrid g;
  g.cascades = std::clamp(cascades, 1, kSunCascadesMax);
  g.sliceAxis = 1;
  g.sun = l;
  g.dims = glm::ivec3(columns, columns, slices + 1);
  g.localCloud = yHi - yLo;
  const float dh = (yHi - yLo) / static_cast<float>(slices);
  // The eye's column: where the sun ray through the eye crosses the layer's bottom, y = yLo.
  const glm::vec2 base = layerIntercept(eye, l, yLo);
  const glm::vec2 centre(glm::dot(base, h), glm::dot(base, glm::vec2(-h.y, h.x)));
  const float stretch = 1.0f / std::abs(l.y);  // along the sun's azimuth (see layerGridMap)
  float du = spacing0;
  for (int k = 0; k < g.cascades; ++k, du *= ratio) {
    const float halfWidth = 0.5f * du * static_cast<float>(columns - 1);
    setCascade(g, k, layerGridMap(l, h, stretch, yLo, yHi, centre - glm::vec2(stretch, 1.0f) * halfWidth, du, dh));
  }
  return g;
}

}  // namespace cloudlut::render
