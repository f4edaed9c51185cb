// `cloudlut compare A.exr B.exr [--diff OUT.png]`: error metrics of image A against the
// reference B over the cloud pixels (reference/SceneCompare.h defines every metric), and a
// false-colour picture of the difference.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/PngImage.h"

#include "cli/Command.h"
#include "cli/Options.h"
#include "core/Errors.h"
#include "io/ExrImage.h"
#include "io/LutIo.h"
#include "reference/SceneCompare.h"

namespace cloudlut::cli {
namespace {

reference::RgbaView viewOf(const io::ExrImage& img, const std::string& path) {
  for (const char* c : {"R", "G", "B"})
    if (!img.has(c)) throw FileError(path, std::string("has no ") + c + " channel (expected linear R, G, B and optionally A)");
  reference::RgbaView v;
  v.width = img.width;
  v.height = img.height;
  v.r = img.channel("R").data();
  v.g = img.channel("G").data();
  v.b = img.channel("B").data();
  v.a = img.has("A") ? img.channel("A").data() : nullptr;
  if (img.has("stderr.R") && img.has("stderr.G") && img.has("stderr.B")) {
    v.seR = img.channel("stderr.R").data();
    v.seG = img.channel("stderr.G").data();
    v.seB = img.channel("stderr.B").data();
  }
  return v;
}

// Signed luminance difference a − b: red where A is brighter, blue where it is darker, black
// where they agree; pixels outside the cloud mask are dark grey. |d| ≥ scale saturates; the
// brightness follows sqrt(|d| / scale) so that small errors stay visible.
void writeDiffPng(const reference::RgbaView& a, const reference::RgbaView& b, double threshold, double scale,
                  const std::string& path) {
  const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
  std::vector<std::uint8_t> rgb(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool cloud = (!a.a && !b.a) || (a.a && a.a[i] > threshold) || (b.a && b.a[i] > threshold);
    unsigned char* o = &rgb[3 * i];
    if (!cloud) {
      o[0] = o[1] = o[2] = 32;
      continue;
    }
    const double ya = 0.2126 * a.r[i] + 0.7152 * a.g[i] + 0.0722 * a.b[i];
    const double yb = 0.2126 * b.r[i] + 0.7152 * b.g[i] + 0.0722 * b.b[i];
    double t = scale > 0 ? (ya - yb) / scale : 0.0;
    if (!std::isfinite(t)) t = 1.0;
    t = std::clamp(t, -1.0, 1.0);
    const double m = std::sqrt(std::abs(t));
    const auto byte = [](double v) { return static_cast<unsigned char>(std::lround(255.0 * std::clamp(v, 0.0, 1.0))); };
    if (t >= 0) {
      o[0] = byte(m);
      o[1] = byte(m * m * 0.6);
      o[2] = 0;
    } else {
      o[0] = 0;
      o[1] = byte(m * m * 0.6);
      o[2] = byte(m);
    }
  }
  io::writePng(path, a.width, a.height, rgb);
}

int runCompare(int argc, char** argv) {
  cxxopts::Options options(
      "cloudlut compare",
      "Compare a render A against a reference B (linear EXR, R, G, B and optionally A = 1 - transmittance).\n"
      "  cloudlut compare A.exr B.exr [--diff OUT.png]\n"
      "Over the pixels where either image has cloud (alpha > threshold) and the three colour channels:\n"
      "  rmse = sqrt(mean((a-b)^2)); rel_rmse = rmse / sqrt(mean(b^2)); bias = mean(a-b); max_error = max|a-b|;\n"
      "  alpha_rmse over the same pixels; ssim = mean SSIM of the Rec. 709 luminance, Gaussian window\n"
      "  sigma 1.5 px (11x11), C1 = (0.01 D)^2, C2 = (0.03 D)^2, D = largest luminance of B.");
  options.add_options()
    ("a", "image to judge (EXR)", cxxopts::value<std::string>())
    ("b", "reference image (EXR)", cxxopts::value<std::string>())
    ("diff", "write a false-colour PNG of the luminance difference A - B (red: A brighter, blue: A darker)",
     cxxopts::value<std::string>())
    ("diff-scale", "luminance difference drawn at full colour (default: the largest difference)",
     cxxopts::value<double>())
    ("threshold", "alpha above which a pixel counts as cloud", cxxopts::value<double>()->default_value("0.01"))
    ("json", "print the metrics as one JSON object");
  options.parse_positional({"a", "b"});
  options.positional_help("A.exr B.exr");
  cxxopts::ParseResult args;
  if (!parseOptions(options, argc, argv, args)) return kExitOk;
  if (!args.count("a") || !args.count("b")) throw UsageError("expected two images: cloudlut compare A.exr B.exr");
  const double threshold = args["threshold"].as<double>();
  if (!(threshold >= 0.0 && threshold < 1.0)) throw UsageError("--threshold must lie in [0, 1)");
  if (args.count("diff")) {
    const std::string d = args["diff"].as<std::string>();
    if (d.size() < 4 || d.substr(d.size() - 4) != ".png") throw UsageError("--diff: expected a .png file name, got '" + d + "'");
  }
  const std::string pathA = args["a"].as<std::string>(), pathB = args["b"].as<std::string>();
  const io::ExrImage imgA = io::readExrImage(pathA);
  const io::ExrImage imgB = io::readExrImage(pathB);
  reference::RgbaView a = viewOf(imgA, pathA);
  const reference::RgbaView b = viewOf(imgB, pathB);
  a.seR = a.seG = a.seB = nullptr;  // only the reference's noise is accounted for
  if (a.width != b.width || a.height != b.height)
    throw FileError(pathB, "is " + std::to_string(b.width) + "x" + std::to_string(b.height) + " but " + pathA + " is " +
                               std::to_string(a.width) + "x" + std::to_string(a.height) + " (sizes must match)");
  const reference::ImageErrors e = reference::compareImages(a, b, threshold);

  if (args.count("json")) {
    std::printf("{\"pixels\": %zu, \"rmse\": %.9g, \"rel_rmse\": %.9g, \"bias\": %.9g, \"rel_bias\": %.9g, "
                "\"ssim\": %.9g, \"max_error\": %.9g, \"alpha_rmse\": %.9g, \"reference_rms\": %.9g",
                e.pixels, e.rmse, e.relativeRmse, e.bias, e.relativeBias, e.ssim, e.maxError, e.alphaRmse,
                e.referenceRms);
    if (e.hasReferenceNoise)
      std::printf(", \"reference_noise\": %.9g, \"nc_rel_rmse\": %.9g", e.referenceNoise,
                  e.noiseCorrectedRelativeRmse);
    std::printf("}\n");
  } else {
    std::printf("pixels      %zu (alpha > %g in either image, of %dx%d)\n", e.pixels, threshold, a.width, a.height);
    std::printf("rmse        %.6g\n", e.rmse);
    std::printf("rel_rmse    %.6g\n", e.relativeRmse);
    std::printf("bias        %.6g\n", e.bias);
    std::printf("rel_bias    %.6g\n", e.relativeBias);
    if (e.hasReferenceNoise) {
      std::printf("ref_noise   %.6g (the reference's relative noise)\n", e.referenceNoise);
      std::printf("nc_rel_rmse %.6g (rel_rmse with the reference's noise removed)\n", e.noiseCorrectedRelativeRmse);
    }
    std::printf("ssim        %.6f\n", e.ssim);
    std::printf("max_error   %.6g\n", e.maxError);
    std::printf("alpha_rmse  %.6g\n", e.alphaRmse);
  }
  if (args.count("diff")) {
    double scale = 0;
    if (args.count("diff-scale")) scale = requirePositive(args["diff-scale"].as<double>(), "diff-scale");
    else {
      const std::size_t n = static_cast<std::size_t>(a.width) * static_cast<std::size_t>(a.height);
      for (std::size_t i = 0; i < n; ++i) {
        const double d = 0.2126 * (a.r[i] - b.r[i]) + 0.7152 * (a.g[i] - b.g[i]) + 0.0722 * (a.b[i] - b.b[i]);
        if (std::isfinite(d)) scale = std::max(scale, std::abs(d));
      }
    }
    writeDiffPng(a, b, threshold, scale, args["diff"].as<std::string>());
    if (!args.count("json")) std::printf("wrote %s (full colour at a luminance difference of %.4g)\n",
                                         args["diff"].as<std::string>().c_str(), scale);
  }
  return kExitOk;
}

const CommandRegistration registration{"compare", "error metrics (RMSE, SSIM, ...) of an EXR render against a reference",
                                       runCompare};

}  // namespace
}  // namespace cloudlut::cli
