#pragma once
// Image error metrics for judging a render against the path-traced ground truth of a particle
// scene (`cloudlut compare`, the ground-truth bench). Both images are linear RGBA (A = 1 −
// transmittance); B is the reference.
//
// The metrics are taken over the cloud pixels only: those where either image's alpha exceeds
// `alphaThreshold` (every pixel when neither image has an alpha channel). Over those pixels and
// the three colour channels:
//   rmse          sqrt(mean((a − b)²))
//   relativeRmse  rmse / sqrt(mean(b²))   (RMSE relative to the reference's RMS radiance)
//   bias          mean(a − b)
//   maxError      max |a − b|
//   alphaRmse     sqrt(mean((A_a − A_b)²)) over the same pixels
//   ssim          mean SSIM of the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B
//                 (Rec. 709), Gaussian window σ = 1.5 px truncated at 11×11 (Wang et al. 2004),
//                 C1 = (0.01·D)², C2 = (0.03·D)², D = the reference's largest luminance (the
//                 images are linear HDR, so the dynamic range is taken from the reference);
//                 the SSIM map is averaged over the cloud pixels. Windows are clipped at the
//                 image border (weights renormalised).
#include <string>
#include <vector>

namespace cloudlut::reference {

struct RgbaView {
  int width = 0, height = 0;
  const float* r = nullptr;
  const float* g = nullptr;
  const float* b = nullptr;
  const float* a = nullptr;  // may be null: no alpha
};

struct ImageErrors {
  std::size_t pixels = 0;       // cloud pixels compared
  double rmse = 0, relativeRmse = 0, bias = 0, maxError = 0, alphaRmse = 0, ssim = 1;
  double referenceRms = 0;      // sqrt(mean(b²)) over the cloud pixels
};

inline constexpr double kDefaultAlphaThreshold = 0.01;

// Throws std::invalid_argument when the sizes differ.
ImageErrors compareImages(const RgbaView& a, const RgbaView& b, double alphaThreshold = kDefaultAlphaThreshold);

// SSIM map of two luminance images (same size), window and constants as above, with the
// dynamic range `range`.
std::vector<double> ssimMap(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                            double range);

}  // namespace cloudlut::reference
