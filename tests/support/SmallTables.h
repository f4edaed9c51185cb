#pragma once
// Small deterministic tables for the io tests.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/Table4D.h"

namespace cloudlut::test {

// A small table with the optical-depth table's axes, `channels` channels and deterministic
// values spread over [lo, hi] (a fixed linear-congruential sequence).
inline cloudlut::Table4D makeTable(std::array<int, 4> dims, int channels, float lo = -0.25f,
                                   float hi = 1.25f, std::uint32_t seed = 1,
                                   const std::string& name = "optical_depth") {
  const double pi = 3.14159265358979323846;
  std::array<cloudlut::Axis, 4> axes = {
      cloudlut::Axis{"phi_s", "rad", 0.0, 2.0 * pi, dims[0], true},
      cloudlut::Axis{"theta_s", "rad", 0.0, pi, dims[1], false},
      cloudlut::Axis{"phi_v", "rad", 0.0, 2.0 * pi, dims[2], true},
      cloudlut::Axis{"theta_v", "rad", 0.0, 0.5 * pi, dims[3], false}};
  std::vector<cloudlut::Channel> names = {{"mean_density", "mean normalized density"},
                                          {"first_matter", "distance to first matter / chord"},
                                          {"extra_b", "test channel"},
                                          {"extra_a", "test channel"}};
  names.resize(static_cast<std::size_t>(channels));
  cloudlut::Table4D table(name, axes, names);
  // built first, then moved in: clang 14 leaks the old value of `json& = {init-list}`
  nlohmann::json parameters = {{"extinction", 0.07}, {"radius", 183.8}, {"model", "test"}};
  table.parameters() = std::move(parameters);
  std::uint32_t state = seed;
  for (float& v : table.data()) {
    state = state * 1664525u + 1013904223u;
    v = lo + (hi - lo) * static_cast<float>(state >> 8) / 16777216.0f;
  }
  return table;
}

}  // namespace cloudlut::test
