#include "io/ContactSheet.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include <stb/stb_easy_font.h>

#include "core/Errors.h"

namespace cloudlut::io {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

// A perceptually ordered dark-blue → teal → green → yellow map (viridis-like), t ∈ [0, 1].
Rgb colourMap(float t) {
  static const float stops[5][3] = {{68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = (t > 0.0f ? std::min(t, 1.0f) : 0.0f) * 4.0f;  // NaN (an overflowed scale) maps to the low end
  const int i = std::min(static_cast<int>(t), 3);
  const float f = t - static_cast<float>(i);
  Rgb c{};
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<std::uint8_t>(std::lround(stops[i][k] + f * (stops[i + 1][k] - stops[i][k])));
  return c;
}

class Canvas {
 public:
  Canvas(int w, int h, Rgb background) : img_{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h * 3)} {
    for (std::size_t i = 0; i < img_.rgb.size(); i += 3) std::copy(background.begin(), background.end(), img_.rgb.begin() + static_cast<std::ptrdiff_t>(i));
  }
  void pixel(int x, int y, Rgb c) {
    if (x < 0 || y < 0 || x >= img_.width || y >= img_.height) return;
    std::uint8_t* p = &img_.rgb[(static_cast<std::size_t>(y) * img_.width + x) * 3];
    p[0] = c[0]; p[1] = c[1]; p[2] = c[2];
  }
  void rect(int x0, int y0, int x1, int y1, Rgb c) {
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) pixel(x, y, c);
  }
  // Text with stb_easy_font (about 6 px per character at scale 1), top-left at (x, y).
  void text(int x, int y, const std::string& s, Rgb c, int scale = 2) {
    static std::vector<char> buffer(1 << 16);
    const int quads = stb_easy_font_print(0.0f, 0.0f, const_cast<char*>(s.c_str()), nullptr, buffer.data(),
                                          static_cast<int>(buffer.size()));
    const float* v = reinterpret_cast<const float*>(buffer.data());
    for (int q = 0; q < quads; ++q) {
      const float* quad = v + q * 16;  // 4 vertices of (x, y, z, colour)
      const float qx0 = quad[0], qy0 = quad[1], qx1 = quad[8], qy1 = quad[9];
      rect(x + static_cast<int>(qx0) * scale, y + static_cast<int>(qy0) * scale, x + static_cast<int>(qx1) * scale,
           y + static_cast<int>(qy1) * scale, c);
    }
  }
  RgbImage take() { return std::move(img_); }

 private:
  RgbImage img_;
};

std::string fmt(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

}  // namespace

RgbImage drawContactSheet(const Table4D& table, const std::string& title, const ContactSheetOptions& options) {
  if (options.channel < 0 || options.channel >= table.channelCount())
    throw UsageError("--channel " + std::to_string(options.channel) + " does not exist (the table has " +
                     std::to_string(table.channelCount()) + ")");
  const auto d = table.dims();
  const auto& axes = table.axes();
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  std::size_t nonFinite = 0;
  for (std::size_t n = 0; n < table.nodeCount(); ++n) {
    const float v = table.at(n, options.channel);
    if (!std::isfinite(v)) { ++nonFinite; continue; }
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (options.range) std::tie(lo, hi) = *options.range;
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    if (options.range) throw UsageError("the colour-scale range must be finite");
    lo = 0.0f;  // no finite value at all
    hi = 1.0f;
  }
  if (!(hi > lo)) hi = lo + 1.0f;
  const double span = static_cast<double>(hi) - static_cast<double>(lo);  // finite in double for any floats

  const int scale = std::max(1, 48 / std::min(d[0], d[1]));
  const int tileW = d[0] * scale, tileH = d[1] * scale, gap = 1;
  int step2 = 1;  // subsampling of axis 2 so the sheet stays within maxWidth
  while ((d[2] + step2 - 1) / step2 * (tileW + gap) > options.maxWidth && step2 < d[2]) ++step2;
  const int cols = (d[2] + step2 - 1) / step2, rows = d[3];
  const int left = 110, top = 76, bottom = 70, right = 16;
  const int width = left + cols * (tileW + gap) + right, height = top + rows * (tileH + gap) + bottom;
  if (static_cast<long long>(width) * height > 400LL * 1000 * 1000)
    throw UsageError("the contact sheet would be " + std::to_string(width) + "x" + std::to_string(height) + " pixels; too large");
  const Rgb white{235, 235, 235}, grey{40, 40, 40}, magenta{255, 0, 255};
  Canvas c(width, height, Rgb{18, 18, 18});

  c.text(8, 6, title + "  channel " + table.channels()[options.channel].name, white);
  c.text(8, 30, "tile: x " + axes[0].name + " [" + fmt(axes[0].min) + ", " + fmt(axes[0].max) + "], y " + axes[1].name +
                    " [" + fmt(axes[1].min) + ", " + fmt(axes[1].max) + "]   columns: " + axes[2].name + " [" +
                    fmt(axes[2].min) + ", " + fmt(axes[2].max) + "]" + (step2 > 1 ? " every " + std::to_string(step2) + " nodes" : "") +
                    "   rows: " + axes[3].name, white);
  c.text(8, 52, std::to_string(nonFinite) + " non-finite values (magenta)", nonFinite ? magenta : white);

  for (int r = 0; r < rows; ++r) {
    c.text(8, top + r * (tileH + gap) + tileH / 2 - 6, fmt(axes[3].value(r)), white, 1);
    for (int col = 0; col < cols; ++col) {
      const int i2 = col * step2;
      const int x0 = left + col * (tileW + gap), y0 = top + r * (tileH + gap);
      c.rect(x0 - gap, y0 - gap, x0 + tileW, y0, grey);
      for (int i1 = 0; i1 < d[1]; ++i1)
        for (int i0 = 0; i0 < d[0]; ++i0) {
          const float v = table.at(table.index(i0, i1, i2, r), options.channel);
          const Rgb colour = std::isfinite(v) ? colourMap(static_cast<float>((static_cast<double>(v) - lo) / span)) : magenta;
          c.rect(x0 + i0 * scale, y0 + i1 * scale, x0 + (i0 + 1) * scale, y0 + (i1 + 1) * scale, colour);
        }
    }
  }
  // Colour scale.
  const int barY = height - bottom + 16, barX = left, barW = std::min(512, width - left - right);
  for (int x = 0; x < barW; ++x) c.rect(barX + x, barY, barX + x + 1, barY + 16, colourMap(static_cast<float>(x) / static_cast<float>(barW - 1)));
  c.text(barX, barY + 22, fmt(lo), white);
  const std::string hiText = fmt(hi);
  c.text(barX + barW - 12 * static_cast<int>(hiText.size()), barY + 22, hiText, white);
  return c.take();
}

}  // namespace cloudlut::io
