// localCloudColumn (lut_formats/glsl/cloudlut_shading.glsl): the cloud a point is in, cut out of
// the sun column through it by a window, checked on columns whose optical-depth profile is
// written here from clouds laid along the sun ray (piecewise-linear τ toward the sun).
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "core/Glsl.h"

namespace {

// A cloud on the sun ray: from s0 to s1 (distance from the sun side, world units), optical
// depth tau spread evenly.
struct Cloud {
  float s0, s1, tau;
};

// Optical depth toward the sun at distance s along the ray (the sun at s = −∞).
float depthAt(const std::vector<Cloud>& clouds, float s) {
  float t = 0.0f;
  for (const Cloud& c : clouds) t += c.tau * std::clamp((s - c.s0) / (c.s1 - c.s0), 0.0f, 1.0f);
  return t;
}

glm::vec3 localAt(const std::vector<Cloud>& clouds, float s, float window) {
  return cloudlut::glsl::localCloudColumn(depthAt(clouds, s), depthAt(clouds, s - window), depthAt(clouds, s + window));
}

}  // namespace

TEST_CASE("localCloudColumn: a cloud behind clear air shadows the point's cloud, it does not join it",
          "[lighting][shading]") {
  // Two clouds 1 km deep, 3 km of clear air between them; a point 400 m into the second one;
  // the window 1.2 km (a bit more than one cloud's depth).
  const std::vector<Cloud> clouds{{0.0f, 1000.0f, 40.0f}, {4000.0f, 5000.0f, 30.0f}};
  const glm::vec3 l = localAt(clouds, 4400.0f, 1200.0f);
  CHECK(l.x == Approx(12.0f).epsilon(1e-5));  // 400 m of the second cloud toward the sun
  CHECK(l.y == Approx(30.0f).epsilon(1e-5));  // the second cloud, whole
  CHECK(l.z == Approx(40.0f).epsilon(1e-5));  // the first cloud, beyond the window
  // A window longer than the whole ray: the whole column, nothing beyond (the previous model).
  const glm::vec3 all = localAt(clouds, 4400.0f, 1.0e5f);
  CHECK(all.x == Approx(52.0f).epsilon(1e-5));
  CHECK(all.y == Approx(70.0f).epsilon(1e-5));
  CHECK(all.z == 0.0f);
}

TEST_CASE("localCloudColumn: the parts add up whatever the point, and out-of-order reads are clamped",
          "[lighting][shading]") {
  const std::vector<Cloud> clouds{{0.0f, 700.0f, 9.0f}, {900.0f, 2500.0f, 55.0f}, {2600.0f, 2700.0f, 2.0f}};
  for (float s = -500.0f; s <= 3500.0f; s += 37.0f) {
    const glm::vec3 l = localAt(clouds, s, 800.0f);
    INFO("s = " << s);
    CHECK(l.x + l.z == Approx(depthAt(clouds, s)).margin(1e-4));  // toward the sun: local + beyond
    CHECK(l.x >= 0.0f);
    CHECK(l.y >= l.x);
    CHECK(l.y <= depthAt(clouds, 1.0e6f) + 1e-4f);
  }
  // Reads from different cascades can disagree: a sunward end deeper than the point, a far end
  // shallower. The point's own optical depth bounds them.
  const glm::vec3 odd = cloudlut::glsl::localCloudColumn(5.0f, 7.0f, 4.0f);
  CHECK(odd.z == 5.0f);
  CHECK(odd.x == 0.0f);
  CHECK(odd.y == 0.0f);
}
