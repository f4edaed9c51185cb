#include "bake/AtmosphereBaker.h"

#include <functional>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "scene/AtmosphereJson.h"

namespace cloudlut::bake {
namespace {

// A 2D RGB table over the unit ranges (x0, x1) ∈ [0, 1]²; axes 2 and 3 are single nodes.
Table4D makeTable(const std::string& name, const char* axis0, const char* axis1, int width, int height,
                  const std::string& meaning) {
  std::array<Axis, 4> axes{};
  axes[0] = Axis{.name = axis0, .unit = "unit", .min = 0.0, .max = 1.0, .size = width};
  axes[1] = Axis{.name = axis1, .unit = "unit", .min = 0.0, .max = 1.0, .size = height};
  axes[2] = Axis{.name = "unused", .unit = "", .min = 0.0, .max = 0.0, .size = 1};
  axes[3] = Axis{.name = "unused", .unit = "", .min = 0.0, .max = 0.0, .size = 1};
  return Table4D(name, axes, {{"r", meaning + ", red"}, {"g", meaning + ", green"}, {"b", meaning + ", blue"}});
}

// Evaluates node(x) at every node of the table, rows in parallel.
void fill(Table4D& table, const std::function<glm::vec3(glm::vec2)>& node) {
  const int w = table.axes()[0].size, h = table.axes()[1].size;
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j)
      for (int i = 0; i < w; ++i) {
        const glm::vec2 x(static_cast<float>(i) / static_cast<float>(w - 1), static_cast<float>(j) / static_cast<float>(h - 1));
        const glm::vec3 v = node(x);
        const std::size_t n = table.index(i, j, 0, 0);
        for (int c = 0; c < 3; ++c) table.at(n, c) = v[c];
      }
  });
}

}  // namespace

glsl::AtmosphereTexture atmosphereTexture(const Table4D& table) {
  const auto d = table.dims();
  if (table.channelCount() != 3 || d[2] != 1 || d[3] != 1)
    throw std::invalid_argument("table '" + table.name() + "' is not an atmosphere table (3 channels, 2 axes)");
  return glsl::AtmosphereTexture{table.data().data(), d[0], d[1]};
}

AtmosphereTables bakeAtmosphere(const glsl::AtmosphereParameters& a, const AtmosphereBakeSettings& s,
                                const ProgressFn& progress) {
  nlohmann::json parameters = {{"atmosphere", scene::atmosphereToJson(a)},
                               {"transmittance_panels", s.transmittancePanels},
                               {"multiple_directions", s.multipleDirections},
                               {"multiple_steps", s.multipleSteps},
                               {"irradiance_directions", s.irradianceDirections},
                               {"irradiance_steps", s.irradianceSteps},
                               {"orders", s.orders == 1 ? nlohmann::json(1) : nlohmann::json("all")}};
  AtmosphereTables t;
  reportProgress(progress, "atmosphere transmittance", 0.0);
  t.transmittance = makeTable("atmosphere_transmittance", "x_mu", "x_r", glsl::CLOUDLUT_TRANSMITTANCE_WIDTH,
                              glsl::CLOUDLUT_TRANSMITTANCE_HEIGHT, "transmittance to the top of the atmosphere");
  fill(t.transmittance, [&](glm::vec2 x) {
    const glm::vec2 rm = glsl::transmittanceRadiusMu(a, x);
    return glm::exp(-glsl::opticalDepthToTop(a, rm.x, rm.y, s.transmittancePanels));
  });
  const glsl::AtmosphereTexture transmittance = atmosphereTexture(t.transmittance);

  reportProgress(progress, "atmosphere multiple scattering", 0.3);
  t.multipleScattering = makeTable("atmosphere_multiple_scattering", "x_mu_s", "x_r", glsl::CLOUDLUT_MULTIPLE_WIDTH,
                                   glsl::CLOUDLUT_MULTIPLE_HEIGHT,
                                   "Psi_ms, radiance of orders >= 2 per unit sun irradiance and scattering coefficient (1/sr)");
  fill(t.multipleScattering, [&](glm::vec2 x) {
    const glm::vec2 rm = glsl::sunTableRadiusMu(a, x);
    return glsl::multipleScatteringNode(a, transmittance, rm.x, rm.y, s.multipleDirections, s.multipleSteps);
  });
  const glsl::AtmosphereTexture multiple = atmosphereTexture(t.multipleScattering);

  reportProgress(progress, "atmosphere irradiance", 0.6);
  t.irradiance = makeTable("atmosphere_irradiance", "x_mu_s", "x_r", glsl::CLOUDLUT_IRRADIANCE_WIDTH,
                           glsl::CLOUDLUT_IRRADIANCE_HEIGHT,
                           "sky irradiance on a horizontal surface per unit sun irradiance");
  const float msWeight = s.orders == 1 ? 0.0f : 1.0f;
  fill(t.irradiance, [&](glm::vec2 x) {
    const glm::vec2 rm = glsl::sunTableRadiusMu(a, x);
    return glsl::skyIrradianceNode(a, transmittance, multiple, rm.x, rm.y, s.irradianceDirections, s.irradianceSteps,
                                   msWeight);
  });
  for (Table4D* table : {&t.transmittance, &t.multipleScattering, &t.irradiance}) table->parameters() = parameters;
  reportProgress(progress, "atmosphere irradiance", 1.0);
  return t;
}

}  // namespace cloudlut::bake
