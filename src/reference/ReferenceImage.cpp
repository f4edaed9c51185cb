#include "reference/ReferenceImage.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace cloudlut::reference {

io::ExrImage renderReferenceScene(const std::vector<scene::Particle>& particles, const scene::View& view,
                                  const Medium& medium, const ScenePtSettings& settings, int width,
                                  int height, const ProgressFn& progress, ReferenceSceneStats* stats,
                                  const DetailNoise& detail) {
  const ReferenceParticle model(medium.model, medium.seed);
  SceneMedium m;
  m.model = &model;
  m.unitOpticalRadius = medium.unitOpticalRadius();
  m.detail = detail.packed();
  for (const scene::Particle& p : particles)
    m.particles.push_back({glm::dvec3(p.center), glm::dmat3(p.toParticle()), static_cast<double>(p.density)});
  if (const std::string problem = mediumWorkProblem(m); !problem.empty())
    throw std::invalid_argument(problem);
  SceneLight light;
  light.sunDirection = glm::normalize(glm::dvec3(view.lighting.sunDirection));
  const glm::vec3 below = view.lighting.skyBelow;
  if (below.x != below.y || below.y != below.z)
    throw std::invalid_argument("the path tracer takes one sky-below fraction for every channel");
  light.skyBelow = static_cast<double>(below.y);
  ScenePtSettings st = settings;
  st.first = medium.first;
  st.later = medium.later;
  const scene::CameraFrame camera(view.camera, width, height);
  const glm::dvec3 eye(camera.eye());
  const auto ray = [&](double px, double py, glm::dvec3& o, glm::dvec3& d) {
    o = eye;
    d = glm::dvec3(camera.rayDirection(static_cast<float>(px), static_cast<float>(py)));
  };
  const ScenePtImage img = renderScene(m, light, st, width, height, ray, progress);
  if (stats) {
    stats->seconds = img.seconds;
    stats->meanVertices = img.meanVertices;
    stats->truncatedPaths = img.truncatedPaths;
  }
  io::ExrImage out(width, height);
  const char* rgb[3] = {"R", "G", "B"};
  const char* se[3] = {"stderr.R", "stderr.G", "stderr.B"};
  const glm::dvec3 sun(view.lighting.sunColor), sky(view.lighting.skyColor);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    const RayEstimate& e = img.pixels[i];
    for (int c = 0; c < 3; ++c) {
      out.channel(rgb[c])[i] = static_cast<float>(sun[c] * (e.single + e.multiple) + sky[c] * e.sky);
      const double var = sun[c] * sun[c] * e.sunSe * e.sunSe + sky[c] * sky[c] * e.skySe * e.skySe +
                         2.0 * sun[c] * sky[c] * e.sunSkyCov;
      out.channel(se[c])[i] = static_cast<float>(std::sqrt(std::max(var, 0.0)));
    }
    out.channel("A")[i] = static_cast<float>(1.0 - e.transmittance);
    out.channel("stderr.A")[i] = static_cast<float>(e.transmittanceSe);
    out.channel("single")[i] = static_cast<float>(e.single);
    out.channel("multiple")[i] = static_cast<float>(e.multiple);
    out.channel("ambient")[i] = static_cast<float>(e.sky);
  }
  char buf[704];
  std::snprintf(buf, sizeof buf,
                "{\"density_model\": \"%s\", \"seed\": %llu, \"unit_optical_radius\": %.9g, \"first_phase\": [%d, %.6g], "
                "\"later_phase\": [%d, %.6g], \"spp\": %d, \"rng_seed\": %llu, \"max_order\": %d, \"jitter\": %s, "
                "\"detail_noise\": [%.6g, %.9g, %d], \"sky_below\": %.6g}",
                toString(medium.model).c_str(), static_cast<unsigned long long>(medium.seed), medium.unitOpticalRadius(),
                glslKind(st.first.kind), static_cast<double>(st.first.param), glslKind(st.later.kind),
                static_cast<double>(st.later.param),
                st.samplesPerPixel, static_cast<unsigned long long>(st.seed), st.maxOrder, st.jitter ? "true" : "false",
                static_cast<double>(detail.enabled() ? detail.amplitude : 0.0f), static_cast<double>(detail.scale),
                detail.seed, light.skyBelow);
  out.attributes["cloudlutReference"] = buf;
  return out;
}

}  // namespace cloudlut::reference
