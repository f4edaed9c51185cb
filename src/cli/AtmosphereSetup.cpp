#include "cli/AtmosphereSetup.h"

#include "bake/AtmosphereBaker.h"
#include "scene/AtmosphereJson.h"

namespace cloudlut::cli {

void setUpAtmosphere(render::Renderer& renderer, const io::LutSet& luts, const scene::Lighting& lighting) {
  if (!lighting.atmosphere) return;
  const glsl::AtmosphereParameters& a = lighting.atmosphereParameters;
  const char* names[3] = {"atmosphere_transmittance", "atmosphere_multiple_scattering", "atmosphere_irradiance"};
  bool stored = luts.manifest.contains("atmosphere") && luts.manifest["atmosphere"] == scene::atmosphereToJson(a);
  for (const char* name : names) stored = stored && luts.tables.count(name) > 0;
  // a set baked before the multiple-scattering table held all six moments (1 or 2 blocks) is
  // baked afresh
  stored = stored && luts.tables.at(names[1]).table.dims()[2] == glsl::CLOUDLUT_MULTIPLE_BLOCKS;
  if (stored) {
    renderer.setAtmosphereTables(a, luts.tables.at(names[0]).table, luts.tables.at(names[1]).table,
                                 luts.tables.at(names[2]).table);
    return;
  }
  const bake::AtmosphereTables t = bake::bakeAtmosphere(a);
  renderer.setAtmosphereTables(a, t.transmittance, t.multipleScattering, t.irradiance);
}

}  // namespace cloudlut::cli
