// The optical-depth suite of `cloudlut bench` (see BenchSuites.h).
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bake/OpticalDepthBaker.h"
#include "bench/BenchSuites.h"
#include "core/Glsl.h"

namespace cloudlut::bench {
namespace {

constexpr int kReferenceSteps = 4096;

std::string resolutionOf(const std::array<int, 4>& d) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) + "x" + std::to_string(d[3]);
}

// Reference values (4096 samples per diameter) of the mean-density channel at a fixed random
// subset of the table's nodes.
struct NodeReference {
  std::vector<std::size_t> nodes;
  std::vector<double> meanDensity;
};

NodeReference referenceAtNodes(const ReferenceParticle& particle, const Table4D& layout, int count) {
  NodeReference ref;
  std::mt19937_64 rng(20141);
  std::uniform_int_distribution<std::size_t> pick(0, layout.nodeCount() - 1);
  for (int i = 0; i < count; ++i) ref.nodes.push_back(pick(rng));
  ref.meanDensity.resize(ref.nodes.size());
  const auto d = layout.dims();
  const auto& axes = layout.axes();
  tbb::parallel_for(std::size_t{0}, ref.nodes.size(), [&](std::size_t k) {
    std::size_t n = ref.nodes[k];
    int idx[4];
    for (int a = 0; a < 4; ++a) {
      idx[a] = static_cast<int>(n % static_cast<std::size_t>(d[a]));
      n /= static_cast<std::size_t>(d[a]);
    }
    const float phiS = static_cast<float>(axes[0].value(idx[0])), thetaS = static_cast<float>(axes[1].value(idx[1]));
    const glm::vec3 S = glsl::sphericalPoint(phiS, thetaS);
    const glm::vec3 v = glsl::frameDirection(glsl::tangentX(phiS, thetaS), glsl::tangentY(phiS), S,
                                             static_cast<float>(axes[2].value(idx[2])),
                                             static_cast<float>(axes[3].value(idx[3])));
    ref.meanDensity[k] = bake::integrateChord(particle, S, v, kReferenceSteps).meanDensity;
  });
  return ref;
}

ErrorStats errorAgainst(const Table4D& table, const NodeReference& ref) {
  std::vector<double> errors;
  errors.reserve(ref.nodes.size());
  for (std::size_t k = 0; k < ref.nodes.size(); ++k)
    errors.push_back(std::fabs(table.at(ref.nodes[k], 0) - ref.meanDensity[k]));
  return summarizeErrors(std::move(errors));
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

void benchOpticalDepth(BenchReport& report, const BenchOptions& options) {
  const int cores = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  bake::OpticalDepthSettings settings;
  if (options.quick) settings.dims = {32, 16, 32, 16};
  const int samples = options.quick ? 1000 : 4000;
  const std::string res = resolutionOf(settings.dims);

  auto bakeTimed = [&](const ReferenceParticle& particle, int steps, int threads, double& seconds) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    bake::OpticalDepthSettings s = settings;
    s.steps = steps;
    const auto t0 = std::chrono::steady_clock::now();
    Table4D table = bake::bakeOpticalDepth(particle, s);
    seconds = secondsSince(t0);
    return table;
  };

  // The default particle, its density grid included in the time.
  {
    reportProgress(options.progress, "bench: optical depth", 0.0);
    for (int threads : {cores, 1}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
      const auto t0 = std::chrono::steady_clock::now();
      const ReferenceParticle particle(DensityModel::Noise, 1);
      const Table4D table = bake::bakeOpticalDepth(particle, settings);
      BenchRow row{"optical-depth", "gauss2", "optical_depth", "noise", res, "", bake::defaultSteps(DensityModel::Noise), threads, secondsSince(t0), -1, -1, -1, -1, "default bake incl. density grid"};
      report.add(row);
    }
  }

  // Time against error, samples per diameter swept, for the noise particle.
  const ReferenceParticle noise(DensityModel::Noise, 1);
  const Table4D shape("shape", bake::opticalDepthAxes(settings.dims), {{"x", ""}});
  const NodeReference noiseRef = referenceAtNodes(noise, shape, samples);
  const std::vector<int> sweep = options.quick ? std::vector<int>{8, 16, 32, 64} : std::vector<int>{4, 8, 16, 24, 32, 48, 64, 96};
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    reportProgress(options.progress, "bench: optical depth", 0.1 + 0.6 * static_cast<double>(i) / static_cast<double>(sweep.size()));
    double seconds = 0.0;
    const Table4D table = bakeTimed(noise, sweep[i], cores, seconds);
    const ErrorStats e = errorAgainst(table, noiseRef);
    BenchRow row{"optical-depth", "gauss2", "optical_depth", "noise", res, "", sweep[i], cores, seconds, e.mean, e.p95, e.max, -1, "error vs 4096 samples"};
    report.add(row);
  }

  // Every model at its default steps.
  int m = 0;
  for (DensityModel model : {DensityModel::Sphere, DensityModel::Radial, DensityModel::Noise,
                             DensityModel::Threshold, DensityModel::Pyroclastic}) {
    reportProgress(options.progress, "bench: optical depth", 0.7 + 0.3 * m++ / 5.0);
    const ReferenceParticle particle(model, 1);
    const NodeReference ref = referenceAtNodes(particle, shape, samples);
    double seconds = 0.0;
    const Table4D table = bakeTimed(particle, 0, cores, seconds);
    const ErrorStats e = errorAgainst(table, ref);
    BenchRow row{"optical-depth", "gauss2", "optical_depth", toString(model), res, "", bake::defaultSteps(model), cores, seconds, e.mean, e.p95, e.max, -1, "default steps; error vs 4096 samples"};
    report.add(row);
  }
  reportProgress(options.progress, "bench: optical depth", 1.0);
}

}  // namespace cloudlut::bench
