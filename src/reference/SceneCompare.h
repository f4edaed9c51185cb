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
//   relativeBias  mean(a − b) / mean(b)
// When B carries its per-pixel standard errors se (a Monte Carlo reference), also:
//   referenceNoise               sqrt(mean(se²)) / sqrt(mean(b²))   (the reference's own relative noise)
//   noiseCorrectedRelativeRmse   sqrt(max(0, mean((a − b)²) − mean(se²))) / sqrt(mean(b²))
// (the expected squared difference to a noisy reference is the squared error plus the
// reference's variance, so the variance is subtracted; meaningful while referenceNoise is well
// below the error measured, e.g. at most a third of it).
//   ssim          mean SSIM of the luminance Y = 0.2126 R + 0.7152 G + 0.0722 B
//                 (Rec. 709), Gaussian window σ = 1.5 px truncated at 11×11 (Wang et al. 2004),
//                 C1 = (0.01·D)², C2 = (0.03·D)², D = the reference's largest luminance (the
//                 images are linear HDR, so the dynamic range is taken from the reference);
//                 the SSIM map is averaged over the cloud pixels. Windows are clipped at the
//                 image border (weights renormalised).
#include <string>
#include <vector>

#include "io/ExrImage.h"

namespace cloudlut::reference {

struct RgbaView {
  int width = 0, height = 0;
  const float* r = nullptr;
  const float* g = nullptr;
  const float* b = nullptr;
  const float* a = nullptr;  // may be null: no alpha
  // Standard errors of R, G, B (a Monte Carlo reference's stderr.R/G/B); may be null.
  const float* seR = nullptr;
  const float* seG = nullptr;
  const float* seB = nullptr;
};

struct ImageErrors {
  std::size_t pixels = 0;       // cloud pixels compared
  double rmse = 0, relativeRmse = 0, bias = 0, maxError = 0, alphaRmse = 0, ssim = 1;
  double referenceRms = 0;      // sqrt(mean(b²)) over the cloud pixels
  double relativeBias = 0;      // mean(a − b) / mean(b)
  bool hasReferenceNoise = false;            // B had standard errors
  double referenceNoise = 0;                 // sqrt(mean(se²)) / rms(b)
  double noiseCorrectedRelativeRmse = 0;     // sqrt(max(0, mse − mean(se²))) / rms(b)
};

inline constexpr double kDefaultAlphaThreshold = 0.01;

// Throws std::invalid_argument when the sizes differ.
ImageErrors compareImages(const RgbaView& a, const RgbaView& b, double alphaThreshold = kDefaultAlphaThreshold);

// compareImages of an interleaved RGBA image (4 floats per pixel, e.g. a render read back)
// against a reference EXR's R, G, B, A and, when it has them, stderr.R/G/B channels.
// Throws std::invalid_argument when the sizes differ.
ImageErrors compareToReference(int width, int height, const float* rgba, const io::ExrImage& reference,
                               double alphaThreshold = kDefaultAlphaThreshold);

// SSIM map of two luminance images (same size), window and constants as above, with the
// dynamic range `range`.
std::vector<double> ssimMap(const std::vector<double>& x, const std::vector<double>& y, int width, int height,
                            double range);

}  // namespace cloudlut::reference
