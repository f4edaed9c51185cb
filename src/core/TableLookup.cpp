#include "core/TableLookup.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/Defaults.h"
#include "core/Glsl.h"
#include "core/ParameterRules.h"

namespace cloudlut {

float unitOpticalRadius(const Table4D& table) {
  const auto& p = table.parameters();
  const double beta = p.value("extinction_per_m", defaults::kExtinctionPerMetre);
  const double radius = p.value("radius_m", defaults::kParticleRadiusMetres);
  return static_cast<float>(beta * radius);
}

float chordOuterThird(const Table4D& opticalDepth) {
  const auto& p = opticalDepth.parameters();
  const auto it = p.find("chord_outer_third_share");
  if (it == p.end()) return 1.0f / 3.0f;
  const double share = it->is_number() ? it->get<double>() : std::numeric_limits<double>::quiet_NaN();
  if (const std::string problem = rules::chordOuterThirdProblem(share); !problem.empty())
    throw std::invalid_argument("chord_outer_third_share " + problem);
  return static_cast<float>(share);
}

OpticalDepthSample lookupOpticalDepth(const Table4D& table, const glm::vec3& S,
                                      const glm::vec3& v, float rho) {
  const glm::vec4 x = glsl::opticalDepthAxes(S, v);
  float values[4] = {0, 0, 0, 0};
  table.sample({x.x, x.y, x.z, x.w}, values);
  OpticalDepthSample s{};
  s.meanDensity = values[0];
  s.firstMatter = table.channelCount() > 1 ? values[1] : 0.0f;
  s.chordLength = glsl::chordLength(glm::normalize(S), v);
  s.opticalDepth = unitOpticalRadius(table) * rho * s.chordLength * s.meanDensity;
  s.transmittance = std::exp(-s.opticalDepth);
  return s;
}

ScatteringStorage scatteringStorage(const Table4D& table) {
  const std::string channel = table.channelCount() ? table.channels()[0].name : std::string();
  if (channel == kSingleScatteringChannel) return ScatteringStorage::Log2MeanSource;
  if (channel == kMultipleScatteringChannel) return ScatteringStorage::MeanSource;
  throw std::runtime_error("table '" + table.name() + "' is not a scattering table of this cloudlut version (channel '" +
                             channel + "', expected '" + kSingleScatteringChannel + "' or '" +
                             kMultipleScatteringChannel + "'): re-bake it");
}

glm::vec4 scatteringAxesRecord(const Table4D& table) {
  const auto& ax = table.axes();
  const float layout = (ax[1].folded ? glsl::CLOUDLUT_LAYOUT_FOLDED_PHI_V : 0.0f) +
                       (ax[3].linearInExp2 ? glsl::CLOUDLUT_LAYOUT_LINEAR_IN_RHO : 0.0f);
  return {static_cast<float>(ax[3].min), static_cast<float>(ax[3].max), static_cast<float>(ax[0].warp), layout};
}

namespace {

// The stored value at the geometry, for a table whose storage is known to be valid.
float sampleStored(const Table4D& table, const glm::vec3& S, const glm::vec3& v, const glm::vec3& l, float rho) {
  const glm::vec4 x = glsl::scatteringAxes(S, v, l, rho, scatteringAxesRecord(table),
                                           static_cast<float>(table.axes()[3].size));
  float value = 0.0f;
  table.sample({x.x, x.y, x.z, x.w}, &value);
  return value;
}

}  // namespace

float sampleScattering(const Table4D& table, const glm::vec3& S, const glm::vec3& v,
                       const glm::vec3& l, float rho) {
  scatteringStorage(table);  // validates
  return sampleStored(table, S, v, l, rho);
}

float scatteringFromStored(ScatteringStorage storage, float stored, float tau) {
  return storage == ScatteringStorage::Log2MeanSource ? glsl::singleScatteringFromTable(stored, tau)
                                                      : glsl::multipleScatteringFromTable(stored, tau);
}

float lookupScattering(const Table4D& table, const glm::vec3& S, const glm::vec3& v,
                       const glm::vec3& l, float rho) {
  const ScatteringStorage storage = scatteringStorage(table);
  const float tau = unitOpticalRadius(table) * rho * glsl::chordLength(glm::normalize(S), v);
  return scatteringFromStored(storage, sampleStored(table, S, v, l, rho), tau);
}

}  // namespace cloudlut
