// The bake's lane kernels give exactly the floats of the code they replace: the AVX2 phase
// product against Eigen's (bake/PhaseProduct.h), and the stencils' eight-lane locate against
// the one-point locate (bake/SphereField.h). Bit for bit, since the tables must not move.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "bake/DirectionGrid.h"
#include "bake/PhaseProduct.h"
#include "bake/SphereField.h"

using namespace cloudlut;

namespace {
// out = M · in as ScatteringOperator's convolvePhase writes it with Eigen (M(i, k) =
// Mt[k·outDirs + i]; in and out row-major with nt columns).
std::vector<float> eigenProduct(const std::vector<float>& Mt, int outDirs, int inDirs, const std::vector<float>& in,
                                int nt) {
  using RowMajor = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<float> out(static_cast<std::size_t>(outDirs) * nt);
  const Eigen::Map<const Eigen::MatrixXf> m(Mt.data(), outDirs, inDirs);
  const Eigen::Map<const RowMajor> a(in.data(), inDirs, nt);
  Eigen::Map<RowMajor> o(out.data(), outDirs, nt);
  o.noalias() = m * a;
  return out;
}

// Whether two field points are the same bits.
bool samePoint(const bake::FieldPoint& a, const bake::FieldPoint& b) {
  return a.offset == b.offset && std::memcmp(a.wr, b.wr, sizeof a.wr) == 0 &&
         std::memcmp(a.wt, b.wt, sizeof a.wt) == 0 && std::memcmp(&a.fb, &b.fb, sizeof a.fb) == 0;
}
}  // namespace

TEST_CASE("The AVX2 phase product equals Eigen's product bit for bit", "[scattering]") {
  // The bake's sizes (312 directions; 32 and 20 zenith nodes; the 544 fine directions of J_2)
  // and small odd ones (depth not a multiple of 8, a last group of 4 rows).
  const int sizes[][3] = {{312, 312, 32}, {312, 312, 20}, {312, 544, 32}, {312, 544, 20}, {8, 13, 12}, {16, 100, 4}};
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (const auto& s : sizes) {
    const int outDirs = s[0], inDirs = s[1], nt = s[2];
    if (!bake::phaseProductAvx2Applies(outDirs, inDirs, nt)) continue;  // no AVX2 here: Eigen runs
    std::vector<float> Mt(static_cast<std::size_t>(outDirs) * inDirs), in(static_cast<std::size_t>(inDirs) * nt);
    for (float& v : Mt) v = u(rng);
    for (float& v : in) v = u(rng);
    const std::vector<float> expected = eigenProduct(Mt, outDirs, inDirs, in, nt);
    std::vector<float> got(expected.size());
    bake::phaseProductAvx2(Mt.data(), outDirs, inDirs, in.data(), nt, got.data());
    INFO("outDirs " << outDirs << ", inDirs " << inDirs << ", nt " << nt);
    CHECK(std::memcmp(got.data(), expected.data(), got.size() * sizeof(float)) == 0);
  }
}

TEST_CASE("The stencils' eight-lane locate equals the one-point locate bit for bit", "[scattering]") {
  const bake::DirectionGrid dirs(24, 13, 1.0);
  const bake::SphereField field(16, 32, 32.0, 0.25, 4.0, dirs);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int ray = 0; ray < 400; ++ray) {
    glm::dvec3 x(u(rng), u(rng), u(rng));
    while (x.x * x.x + x.y * x.y + x.z * x.z > 1.0) x *= 0.5;  // inside the sphere
    // the node directions, and the poles and the axis (the folded azimuth's edge cases)
    const glm::dvec3 w = ray % 5 == 0 ? glm::dvec3(0.0, 0.0, ray % 2 ? 1.0 : -1.0) : dirs.direction(ray % dirs.count());
    const glm::dvec3 origin = ray % 7 == 0 ? glm::dvec3(0.0, 0.0, x.z) : x;
    const double wh = std::hypot(w.x, w.y);
    const int n = 1 + ray % 8;
    double s[8];
    glm::dvec3 y[8];
    for (int k = 0; k < n; ++k) {
      s[k] = 0.25 * k * (1.0 + u(rng)) / 2.0;
      y[k] = origin - s[k] * w;
    }
    bake::FieldPoint onRay[8], atPoints[8];
    field.locateRay8(origin, w, wh, s, n, onRay);
    field.locatePoints8(y, w, wh, n, atPoints);
    for (int k = 0; k < n; ++k) {
      CHECK(samePoint(onRay[k], field.locate(origin - s[k] * w, w, wh)));
      CHECK(samePoint(atPoints[k], field.locate(y[k], w, wh)));
      ++compared;
    }
  }
  CHECK(compared > 1000);
}
