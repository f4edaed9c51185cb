#include "reference/SceneCompare.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cloudlut::reference {

namespace {
constexpr int kRadius = 5;       // 11×11 window
constexpr double kSigma = 1.5;   // Gaussian σ, pixels

double luminance(double r, double g, double b) { return 0.2126 * r + 0.7152 * g + 0.0722 * b; }
}  // namespace

std::vector<double> ssimMap(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                            double range) {
  double kernel[2 * kRadius + 1];
  for (int i = -kRadius; i <= kRadius; ++i) kernel[i + kRadius] = std::exp(-0.5 * i * i / (kSigma * kSigma));
  const double c1 = (0.01 * range) * (0.01 * range), c2 = (0.03 * range) * (0.03 * range);
  std::vector<double> out(x.size(), 1.0);
  for (int py = 0; py < height; ++py)
    for (int px = 0; px < width; ++px) {
      double sw = 0, mx = 0, my = 0, sxx = 0, syy = 0, sxy = 0;
      for (int dy = -kRadius; dy <= kRadius; ++dy) {
        const int yy = py + dy;
        if (yy < 0 || yy >= height) continue;
        for (int dx = -kRadius; dx <= kRadius; ++dx) {
          const int xx = px + dx;
          if (xx < 0 || xx >= width) continue;
          const double w = kernel[dy + kRadius] * kernel[dx + kRadius];
          const std::size_t i = static_cast<std::size_t>(yy) * width + xx;
          sw += w;
          mx += w * x[i];
          my += w * y[i];
          sxx += w * x[i] * x[i];
          syy += w * y[i] * y[i];
          sxy += w * x[i] * y[i];
        }
      }
      mx /= sw;
      my /= sw;
      const double vx = std::max(sxx / sw - mx * mx, 0.0), vy = std::max(syy / sw - my * my, 0.0);
      const double cxy = sxy / sw - mx * my;
      out[static_cast<std::size_t>(py) * width + px] =
          ((2 * mx * my + c1) * (2 * cxy + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
    }
  return out;
}

ImageErrors compareImages(const RgbaView& a, const RgbaView& b, double alphaThreshold) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("image sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                                " and " + std::to_string(b.width) + "x" + std::to_string(b.height));
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  std::vector<char> mask(n, 1);
  if (a.a || b.a)
    for (std::size_t i = 0; i < n; ++i)
      mask[i] = (a.a && a.a[i] > alphaThreshold) || (b.a && b.a[i] > alphaThreshold);

  ImageErrors e;
  double sum2 = 0, sumRef2 = 0, sum = 0, sumRef = 0, alpha2 = 0, se2 = 0;
  const bool noise = b.seR && b.seG && b.seB;
  std::vector<double> ya(n), yb(n);
  double range = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double ca[3] = {a.r[i], a.g[i], a.b[i]}, cb[3] = {b.r[i], b.g[i], b.b[i]};
    ya[i] = luminance(ca[0], ca[1], ca[2]);
    yb[i] = luminance(cb[0], cb[1], cb[2]);
    if (std::isfinite(yb[i])) range = std::max(range, yb[i]);
    if (!mask[i]) continue;
    ++e.pixels;
    for (int c = 0; c < 3; ++c) {
      const double d = ca[c] - cb[c];
      sum += d;
      sum2 += d * d;
      sumRef2 += cb[c] * cb[c];
      sumRef += cb[c];
      e.maxError = std::max(e.maxError, std::abs(d));
    }
    if (noise) se2 += double(b.seR[i]) * b.seR[i] + double(b.seG[i]) * b.seG[i] + double(b.seB[i]) * b.seB[i];
    const double da = (a.a ? a.a[i] : 1.0) - (b.a ? b.a[i] : 1.0);
    alpha2 += da * da;
  }
  if (e.pixels == 0) return e;
  const double count = 3.0 * static_cast<double>(e.pixels);
  e.rmse = std::sqrt(sum2 / count);
  e.bias = sum / count;
  e.referenceRms = std::sqrt(sumRef2 / count);
  e.relativeRmse = e.referenceRms > 0 ? e.rmse / e.referenceRms : (e.rmse > 0 ? INFINITY : 0.0);
  e.alphaRmse = std::sqrt(alpha2 / static_cast<double>(e.pixels));
  e.relativeBias = sumRef != 0 ? sum / sumRef : 0.0;
  if (noise && e.referenceRms > 0) {
    e.hasReferenceNoise = true;
    e.referenceNoise = std::sqrt(se2 / count) / e.referenceRms;
    e.noiseCorrectedRelativeRmse = std::sqrt(std::max(0.0, (sum2 - se2) / count)) / e.referenceRms;
  }
  const std::vector<double> map = ssimMap(ya, yb, a.width, a.height, std::max(range, 1e-6));
  double s = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (mask[i]) s += map[i];
  e.ssim = s / static_cast<double>(e.pixels);
  return e;
}

ImageErrors compareToReference(int width, int height, const float* rgba, const io::ExrImage& reference,
                               double alphaThreshold) {
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  std::vector<float> planes(4 * n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t c = 0; c < 4; ++c) planes[c * n + i] = rgba[4 * i + c];
  const RgbaView a{width, height, planes.data(), planes.data() + n, planes.data() + 2 * n, planes.data() + 3 * n};
  const auto channel = [&](const char* name) { return reference.has(name) ? reference.channel(name).data() : nullptr; };
  const RgbaView b{reference.width,   reference.height,     channel("R"),       channel("G"),      channel("B"),
                   channel("A"),      channel("stderr.R"),  channel("stderr.G"), channel("stderr.B")};
  if (!b.r || !b.g || !b.b) throw std::invalid_argument("the reference has no R, G, B channels");
  return compareImages(a, b, alphaThreshold);
}

}  // namespace cloudlut::reference
