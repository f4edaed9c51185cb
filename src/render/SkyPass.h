#pragma once
// The sky pass (issue 13): the frame composited under a precomputed atmosphere
// (lut_formats/glsl/cloudlut_atmosphere*.glsl, the tables of bake/AtmosphereBaker.h uploaded by
// setTables). Per frame, on the GPU:
//   sky view     192 × 108 in-scattered radiance toward every direction from the camera
//                (shaders/sky_view.comp.glsl; Hillaire 2020 §5.3);
//   aerial       32 × 32 × 32 in-scattering, its single scattering of sunlight and transmittance
//                over the camera's frustum to 100 km (shaders/sky_aerial.comp.glsl; Hillaire
//                2020 §5.4);
//   shafts       with light shafts and a sun volume: the single scattering the clouds' shadow
//                takes from the air (seed §5.6), per screen cell of kShaftCell² pixels at the
//                aerial slices, kShaftPieces sun-volume samples per slice's stretch of the ray
//                inside the volume (shaders/sky_shafts.comp.glsl, sky_shafts.glsl);
//   composite    sky, sun disc, ground lit through the clouds' shadow, aerial perspective on
//                the clouds, the shafts' loss (shaders/sky_composite.comp.glsl).
// The clouds' sunlight and ambient come from the same tables (cloudLighting).
#include <array>
#include <string>

#include <glm/vec2.hpp>

#include "core/Glsl.h"
#include "core/Table4D.h"
#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/GpuStorage.h"
#include "render/RenderTypes.h"
#include "render/SunVolume.h"

namespace cloudlut::render {

class SkyPass {
 public:
  SkyPass(const GlFunctions& gl, const GlContext& context);
  ~SkyPass();
  SkyPass(const SkyPass&) = delete;
  SkyPass& operator=(const SkyPass&) = delete;

  // The atmosphere and its three tables (transmittance, multiple scattering, irradiance; copied
  // to the CPU side for cloudLighting and uploaded as textures).
  void setTables(const glsl::AtmosphereParameters& atmosphere, const Table4D& transmittance,
                 const Table4D& multipleScattering, const Table4D& irradiance);
  bool hasTables() const { return transmittanceTexture_ != 0; }

  // The lighting of clouds at altitude `altitude` (m above the ground): the sun's colour times
  // the atmosphere's transmittance toward it, and as the ambient sky radiance the sky's
  // irradiance on a horizontal surface over π (the radiance of a uniform sky of that irradiance
  // above the horizon), times the sun's colour, and below the horizon the ground albedo times that
  // (Lighting::skyBelow); with `orders` 1 the irradiance of single scattering is not separated, so
  // the table's is used as baked.
  scene::Lighting cloudLighting(const scene::Lighting& lighting, float altitude) const;

  // Composites `image` (the clouds: premultiplied radiance, opacity, distance) under the sky in
  // place; `sun` (built when `sunBuilt`) shadows the ground, through slabTransmittance with the
  // clouds' later phase asymmetry `laterAsymmetry` (dimensionless).
  void composite(Image& image, const RenderSettings& settings, const SunVolume& sun, bool sunBuilt, float laterAsymmetry);

  static constexpr int kSkyViewWidth = 192, kSkyViewHeight = 108;
  static constexpr int kAerialSize = 32, kAerialSlices = 32;
  static constexpr float kAerialMaxMetres = 100e3f;
  static constexpr int kShaftCell = 8;    // pixels per side of a light-shaft cell
  static constexpr int kShaftPieces = 4;  // sun-volume samples per aerial slice

 private:
  void setCommonUniforms(const ProgramUniforms& u, const RenderSettings& s) const;

  const GlFunctions& gl_;
  const GlContext& context_;
  glsl::AtmosphereParameters atmosphere_ = glsl::defaultAtmosphere();
  Table4D transmittance_, multiple_, irradiance_;
  GLuint transmittanceTexture_ = 0, multipleTexture_ = 0, irradianceTexture_ = 0;
  GLuint skyView_ = 0, aerialInScatter_ = 0, aerialTransmittance_ = 0, aerialSingle_ = 0;
  GLuint shaftLoss_ = 0;          // cells × AERIAL_SLICES, sized for shaftCells_
  glm::ivec2 shaftCells_{0, 0};
  GlProgram viewProgram_, aerialProgram_, shaftsProgram_, compositeProgram_;
  StorageBuffer colour_, distance_;
};

}  // namespace cloudlut::render
