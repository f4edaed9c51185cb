#pragma once
// The atmosphere's sun-independent tables (lut_formats/glsl/cloudlut_atmosphere_tables.glsl):
// transmittance T(r, mu) 256 × 128, multiple scattering Ψms(r, mu_s) and the field's other
// moments 32 × 32 × 6 (axis 2 the block) and sky irradiance E(r, mu_s) 64 × 16, RGB, each a Table4D whose
// axis 3 has one node (axis 2 too but for the multiple-scattering table). Each node is the
// shared GLSL's integral (opticalDepthToTop, multipleScatteringNode, skyIrradianceNode); the
// multiple-scattering table needs the transmittance table and the irradiance table both. Ψms is
// the sum of the orders 1 … multipleOrders of scatteringOrderNode, each from the one below, plus
// a geometric tail (multipleScatteringFromOrders).
#include "core/Glsl.h"
#include "core/Progress.h"
#include "core/Table4D.h"

namespace cloudlut::bake {

struct AtmosphereBakeSettings {
  int transmittancePanels = 32;  // two-point Gauss–Legendre panels per ray (64 extinction samples)
  int multipleDirections = 8;    // 8 × 8 directions per Ψms node (Hillaire 2020: 64), zenith bins crowded at the horizon
  int multipleSteps = 16;        // pieces per direction (40 change the sky by < 0.1%)
  // Ψms by scattering orders computed one at a time (scatteringOrderNode), this many before the
  // geometric tail; 0 = Hillaire 2020's series from the second order alone (multipleScatteringNode).
  int multipleOrders = 3;  // 4 change the bench's errors by < 0.1%
  // Whether Ψms adds the geometric tail beyond multipleOrders (false: the orders 1 … multipleOrders
  // alone, so that the sky's orders 2 … multipleOrders + 1 can be checked one at a time).
  bool multipleTail = true;
  int irradianceDirections = 8;  // 8 × 8 directions over a mirrored half hemisphere
  int irradianceSteps = 24;      // pieces per direction
  // Orders in the irradiance table: 1 = single scattering only, anything else = all (Ψms).
  int orders = 0;
};

struct AtmosphereTables {
  Table4D transmittance;        // "atmosphere_transmittance"
  Table4D multipleScattering;   // "atmosphere_multiple_scattering"
  Table4D irradiance;           // "atmosphere_irradiance"
};

// Bakes the three tables in parallel over rows (oneTBB): the same output for any thread count.
// Each table's parameters hold the atmosphere (scene/AtmosphereJson.h) and the settings.
AtmosphereTables bakeAtmosphere(const glsl::AtmosphereParameters& atmosphere, const AtmosphereBakeSettings& settings = {},
                                const ProgressFn& progress = {});

// The shared GLSL's view of a table baked (or read) as above: its texels, width and height.
// The table must outlive the returned value; throws std::invalid_argument unless the table has
// 3 channels, one node on axis 3 and at most two on axis 2 (the blocks, stacked along the height).
glsl::AtmosphereTexture atmosphereTexture(const Table4D& table);

}  // namespace cloudlut::bake
