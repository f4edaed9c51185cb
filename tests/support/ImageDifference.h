#pragma once
// The colour of one rendered image against another over a window of pixels: what a test of
// "the same view, rendered two ways" measures.
#include <cmath>
#include <cstddef>

#include "render/RenderTypes.h"

namespace cloudlut::test {

struct ColourDifference {
  double relativeRmse = 0.0;  // sqrt(Σ (a − r)² / Σ r²) over R, G, B (dimensionless)
  double relativeBias = 0.0;  // Σ (a − r) / Σ r
  std::size_t pixels = 0;     // pixels counted: cloud (opacity above `cloud`) in either image
};

// Image a's window of w×h pixels from (ax, ay) against reference r's from (rx, ry), over the
// pixels where either image's opacity A exceeds `cloud`.
inline ColourDifference colourDifference(const render::Image& a, int ax, int ay, const render::Image& r, int rx,
                                         int ry, int w, int h, float cloud = 0.01f) {
  double squares = 0.0, reference = 0.0, difference = 0.0, sum = 0.0;
  ColourDifference out;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float* pa = a.pixel(ax + x, ay + y);
      const float* pr = r.pixel(rx + x, ry + y);
      if (pa[3] <= cloud && pr[3] <= cloud) continue;
      ++out.pixels;
      for (int c = 0; c < 3; ++c) {
        const double d = double(pa[c]) - pr[c];
        squares += d * d;
        reference += double(pr[c]) * pr[c];
        difference += d;
        sum += pr[c];
      }
    }
  out.relativeRmse = reference > 0.0 ? std::sqrt(squares / reference) : 0.0;
  out.relativeBias = sum > 0.0 ? difference / sum : 0.0;
  return out;
}

// The whole of a against the whole of r (the same size).
inline ColourDifference colourDifference(const render::Image& a, const render::Image& r, float cloud = 0.01f) {
  return colourDifference(a, 0, 0, r, 0, 0, r.width, r.height, cloud);
}

}  // namespace cloudlut::test
