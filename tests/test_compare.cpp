// `cloudlut compare` and the metrics of reference/SceneCompare.h.
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include "support/CliRunner.h"
#include "io/ExrImage.h"
#include "reference/SceneCompare.h"

using namespace cloudlut;
using namespace cloudlut::test;

namespace {

// A smooth cloud-like test image: a disc of alpha with radiance varying across it.
io::ExrImage testImage(int w, int h, double offset = 0.0) {
  io::ExrImage img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * w + x;
      const double dx = (x - 0.5 * w) / (0.35 * w), dy = (y - 0.5 * h) / (0.35 * h);
      const double r2 = dx * dx + dy * dy;
      const double a = r2 < 1.0 ? 1.0 - r2 : 0.0;
      img.channel("A")[i] = static_cast<float>(a);
      const double base = a > 0 ? 0.3 + 0.2 * std::sin(0.3 * x) * std::cos(0.2 * y) + offset : 0.0;
      img.channel("R")[i] = static_cast<float>(base);
      img.channel("G")[i] = static_cast<float>(base * 0.9 + (a > 0 ? 0.1 * offset : 0.0));
      img.channel("B")[i] = static_cast<float>(base * 0.8 + (a > 0 ? 0.2 * offset : 0.0));
    }
  return img;
}

nlohmann::json runJson(const std::string& args) {
  const CliResult r = runCli("compare " + args + " --json");
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  return nlohmann::json::parse(r.out);
}

}  // namespace

TEST_CASE("compare: identical images have zero error and SSIM 1", "[compare]") {
  TempDir dir;
  io::writeExrImage(testImage(48, 32), dir / "a.exr");
  const auto j = runJson("'" + (dir / "a.exr").string() + "' '" + (dir / "a.exr").string() + "'");
  CHECK(j["pixels"].get<int>() > 100);
  CHECK(j["rmse"].get<double>() == 0.0);
  CHECK(j["bias"].get<double>() == 0.0);
  CHECK(j["max_error"].get<double>() == 0.0);
  CHECK(j["ssim"].get<double>() == Approx(1.0).margin(1e-12));
}

TEST_CASE("compare: a known perturbation gives the expected RMSE, bias and maximum", "[compare]") {
  TempDir dir;
  // A = B + δ on every cloud pixel in R, G + 0.1δ·..., so per channel the differences are
  // δ, 0.9δ + 0.1δ = δ, 0.8δ + 0.2δ = δ: exactly δ everywhere in the cloud.
  const double delta = 0.01;
  io::writeExrImage(testImage(48, 32, delta), dir / "a.exr");
  io::writeExrImage(testImage(48, 32), dir / "b.exr");
  const auto j = runJson("'" + (dir / "a.exr").string() + "' '" + (dir / "b.exr").string() + "' --diff '" +
                         (dir / "d.png").string() + "'");
  CHECK(j["rmse"].get<double>() == Approx(delta).epsilon(1e-4));
  CHECK(j["bias"].get<double>() == Approx(delta).epsilon(1e-4));
  CHECK(j["max_error"].get<double>() == Approx(delta).epsilon(1e-4));
  CHECK(j["rel_rmse"].get<double>() == Approx(delta / j["reference_rms"].get<double>()).epsilon(1e-6));
  CHECK(j["ssim"].get<double>() < 1.0);
  CHECK(j["ssim"].get<double>() > 0.9);
  CHECK(std::filesystem::file_size(dir / "d.png") > 0);

  // The metrics straight from the library: a single-pixel change of known size.
  io::ExrImage b = testImage(16, 16), a = b;
  const std::size_t i = 8 * 16 + 8;
  a.channel("R")[i] += 0.3f;
  auto view = [](const io::ExrImage& img) {
    return reference::RgbaView{img.width, img.height, img.channel("R").data(), img.channel("G").data(),
                               img.channel("B").data(), img.channel("A").data()};
  };
  const auto e = reference::compareImages(view(a), view(b));
  CHECK(e.rmse == Approx(std::sqrt(0.09 / (3.0 * static_cast<double>(e.pixels)))).epsilon(1e-5));
  CHECK(e.maxError == Approx(0.3).epsilon(1e-5));
}

TEST_CASE("compare: bad input fails naming the file, sizes must match", "[compare]") {
  TempDir dir;
  io::writeExrImage(testImage(48, 32), dir / "a.exr");
  io::writeExrImage(testImage(40, 32), dir / "small.exr");
  {
    std::ofstream junk(dir / "junk.exr");
    junk << "not an image";
  }
  io::ExrImage noRgb(8, 8);
  noRgb.channel("Y");
  io::writeExrImage(noRgb, dir / "y.exr");
  const std::string a = "'" + (dir / "a.exr").string() + "'";

  const auto missing = runCli("compare " + a + " '" + (dir / "missing.exr").string() + "'");
  CHECK(missing.exitCode == 1);
  CHECK(missing.err.find("missing.exr") != std::string::npos);
  const auto junk = runCli("compare '" + (dir / "junk.exr").string() + "' " + a);
  CHECK(junk.exitCode == 1);
  CHECK(junk.err.find("junk.exr") != std::string::npos);
  const auto y = runCli("compare " + a + " '" + (dir / "y.exr").string() + "'");
  CHECK(y.exitCode == 1);
  CHECK(y.err.find("y.exr") != std::string::npos);
  const auto size = runCli("compare " + a + " '" + (dir / "small.exr").string() + "'");
  CHECK(size.exitCode == 1);
  CHECK(size.err.find("sizes must match") != std::string::npos);
  CHECK(size.err.find("40x32") != std::string::npos);
  const auto one = runCli("compare " + a);
  CHECK(one.exitCode == 2);
  const auto badDiff = runCli("compare " + a + " " + a + " --diff out.jpg");
  CHECK(badDiff.exitCode == 2);
}
