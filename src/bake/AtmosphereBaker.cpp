#include "bake/AtmosphereBaker.h"

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "scene/AtmosphereJson.h"

namespace cloudlut::bake {
namespace {

// A 2D RGB table over the unit ranges (x0, x1) ∈ [0, 1]², `blocks` of them along axis 2 (block b
// holds the b-th quantity on the same grid); axis 3 is a single node.
Table4D makeTable(const std::string& name, const char* axis0, const char* axis1, int width, int height,
                  const std::string& meaning, int blocks = 1) {
  std::array<Axis, 4> axes{};
  axes[0] = Axis{.name = axis0, .unit = "unit", .min = 0.0, .max = 1.0, .size = width};
  axes[1] = Axis{.name = axis1, .unit = "unit", .min = 0.0, .max = 1.0, .size = height};
  axes[2] = blocks == 1 ? Axis{.name = "unused", .unit = "", .min = 0.0, .max = 0.0, .size = 1}
                        : Axis{.name = "block", .unit = "index", .min = 0.0, .max = double(blocks - 1), .size = blocks};
  axes[3] = Axis{.name = "unused", .unit = "", .min = 0.0, .max = 0.0, .size = 1};
  return Table4D(name, axes, {{"r", meaning + ", red"}, {"g", meaning + ", green"}, {"b", meaning + ", blue"}});
}

// Evaluates node(x) at every node of block 0 of the table, rows in parallel.
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

constexpr int kW = glsl::CLOUDLUT_MULTIPLE_WIDTH, kH = glsl::CLOUDLUT_MULTIPLE_HEIGHT;
constexpr int kBlocks = glsl::CLOUDLUT_MULTIPLE_BLOCKS;
constexpr std::size_t kBlock = std::size_t(3) * kW * kH;  // floats in one W × H RGB block

// One scattering order on the multiple-scattering grid: its six moments in the table's layout
// (block 0 J, 1 Myy, 2 Mxx, 3 Mxy, 4 Dx, 5 Dy) and E_n in one block.
struct OrderArrays {
  std::vector<float> moments = std::vector<float>(kBlocks * kBlock, 0.0f);
  std::vector<float> irradiance = std::vector<float>(kBlock, 0.0f);
};

// Order n from order n − 1 (`previous`, ignored when fromSun), rows in parallel.
OrderArrays computeOrder(const glsl::AtmosphereParameters& a, const glsl::AtmosphereTexture& transmittance,
                         const OrderArrays* previous, const AtmosphereBakeSettings& s) {
  OrderArrays out;
  const bool fromSun = previous == nullptr;
  const glsl::AtmosphereTexture pm = fromSun ? transmittance : glsl::AtmosphereTexture{previous->moments.data(), kW, kBlocks * kH};
  const glsl::AtmosphereTexture pe = fromSun ? transmittance : glsl::AtmosphereTexture{previous->irradiance.data(), kW, kH};
  tbb::parallel_for(tbb::blocked_range<int>(0, kH), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j != rows.end(); ++j)
      for (int i = 0; i < kW; ++i) {
        const glm::vec2 x(static_cast<float>(i) / static_cast<float>(kW - 1), static_cast<float>(j) / static_cast<float>(kH - 1));
        const glm::vec2 rm = glsl::sunTableRadiusMu(a, x);
        const glsl::ScatteringOrder o = glsl::scatteringOrderNode(a, transmittance, pm, pe, rm.x, rm.y, s.multipleDirections,
                                                                  s.multipleSteps, fromSun);
        const std::size_t n = 3 * (std::size_t(j) * kW + i);
        const glm::vec3 blocks[kBlocks] = {o.average, o.momentYY, o.momentXX, o.momentXY, o.dipoleX, o.dipoleY};
        for (int c = 0; c < 3; ++c) {
          for (int b = 0; b < kBlocks; ++b) out.moments[b * kBlock + n + c] = blocks[b][c];
          out.irradiance[n + c] = o.irradiance[c];
        }
      }
  });
  return out;
}

// Ψms and its moments by orders: 1 … N one at a time, summed, plus the geometric tail beyond N.
void fillMultipleByOrders(Table4D& table, const glsl::AtmosphereParameters& a, const glsl::AtmosphereTexture& transmittance,
                          const AtmosphereBakeSettings& s) {
  std::vector<float> sum(kBlocks * kBlock, 0.0f);
  OrderArrays last, previous;
  for (int order = 1; order <= s.multipleOrders; ++order) {
    OrderArrays next = computeOrder(a, transmittance, order == 1 ? nullptr : &last, s);
    previous = std::move(last);
    last = std::move(next);
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += last.moments[k];
  }
  const auto at = [](const std::vector<float>& v, std::size_t k) { return glm::vec3(v[k], v[k + 1], v[k + 2]); };
  for (std::size_t k = 0; k < kBlock; k += 3) {
    // the ratio of the last two orders' averages (block 0); none with one order or without the
    // tail (q = 0: the sum of the orders baked, exactly)
    const glm::vec3 q = s.multipleTail && s.multipleOrders > 1
                            ? glsl::multipleScatteringOrderRatio(at(last.moments, k), at(previous.moments, k))
                            : glm::vec3(0.0f);
    for (int b = 0; b < kBlocks; ++b) {
      const std::size_t m = b * kBlock + k;
      const glm::vec3 v = glsl::multipleScatteringFromOrders(at(sum, m), at(last.moments, m), q);
      for (int c = 0; c < 3; ++c) table.data()[m + c] = v[c];
    }
  }
}

}  // namespace

glsl::AtmosphereTexture atmosphereTexture(const Table4D& table) {
  const auto d = table.dims();
  if (table.channelCount() != 3 || (d[2] != 1 && d[2] != kBlocks) || d[3] != 1)
    throw std::invalid_argument("table '" + table.name() + "' is not an atmosphere table (3 channels, 2 axes, 1 or " +
                                std::to_string(kBlocks) + " blocks)");
  return glsl::AtmosphereTexture{table.data().data(), d[0], d[1] * d[2]};
}

AtmosphereTables bakeAtmosphere(const glsl::AtmosphereParameters& a, const AtmosphereBakeSettings& s,
                                const ProgressFn& progress) {
  nlohmann::json parameters = {{"atmosphere", scene::atmosphereToJson(a)},
                               {"transmittance_panels", s.transmittancePanels},
                               {"multiple_directions", s.multipleDirections},
                               {"multiple_steps", s.multipleSteps},
                               {"multiple_orders", s.multipleOrders},
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
                                   "moments of the radiance of orders >= 1 arriving, per unit sun irradiance (1/sr): "
                                   "block 0 Psi_ms, 1 Myy, 2 Mxx, 3 Mxy, 4 Dx, 5 Dy",
                                   kBlocks);
  if (s.multipleOrders > 0) {
    fillMultipleByOrders(t.multipleScattering, a, transmittance, s);
  } else {
    fill(t.multipleScattering, [&](glm::vec2 x) {
      const glm::vec2 rm = glsl::sunTableRadiusMu(a, x);
      return glsl::multipleScatteringNode(a, transmittance, rm.x, rm.y, s.multipleDirections, s.multipleSteps);
    });
    // the series' field is isotropic: Myy = Mxx = J / 3, Mxy = Dx = Dy = 0
    std::vector<float>& data = t.multipleScattering.data();
    for (std::size_t k = 0; k < kBlock; ++k) data[kBlock + k] = data[2 * kBlock + k] = data[k] / 3.0f;
  }
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
