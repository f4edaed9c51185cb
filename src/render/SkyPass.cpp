#include "render/SkyPass.h"

#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "core/Errors.h"
#include "render/ShaderSources.h"

namespace cloudlut::render {
namespace {

constexpr int kTransmittanceUnit = 0, kMultipleUnit = 1, kIrradianceUnit = 2, kSkyViewUnit = 3;
constexpr int kAerialInScatterUnit = 4, kAerialTransmittanceUnit = 5, kSunVolumeUnit = 6, kAerialSingleUnit = 7;
constexpr int kShaftLossUnit = 8;
constexpr GLuint kColourBinding = 7, kDistanceBinding = 8;
constexpr unsigned kCompositeGroup = 64, kTileGroup = 8;

const std::vector<std::string> kAtmosphereFiles = {"cloudlut_geometry.glsl", "cloudlut_phase.glsl", "sky_textures.glsl",
                                                   "cloudlut_atmosphere.glsl", "cloudlut_atmosphere_tables.glsl",
                                                   "cloudlut_atmosphere_sky.glsl", "sky_uniforms.glsl"};

std::vector<std::string> withFiles(std::vector<std::string> files, const std::vector<std::string>& more) {
  files.insert(files.end(), more.begin(), more.end());
  return files;
}

GLuint uploadTable(const GlFunctions& gl, const GlContext& context, const Table4D& t) {
  const auto d = t.dims();
  return createFloatTexture3D(gl, context, t.name(), d[0], d[1] * d[2], 1, 3, t.data().data());  // blocks stacked
}

void bindTexture3D(const GlFunctions& gl, const ProgramUniforms& u, const char* name, int unit, GLuint texture) {
  gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl.BindTexture(GL_TEXTURE_3D, texture);
  u.set(name, unit);
}

}  // namespace

SkyPass::SkyPass(const GlFunctions& gl, const GlContext& context)
    : gl_(gl), context_(context), colour_(gl), distance_(gl) {
  const std::string aerial = glslDefine("AERIAL_SIZE", kAerialSize) + glslDefine("AERIAL_SLICES", kAerialSlices);
  viewProgram_ = linkComputeProgram(gl, withFiles(kAtmosphereFiles, {"sky_view.comp.glsl"}), "");
  aerialProgram_ = linkComputeProgram(gl, withFiles(kAtmosphereFiles, {"sky_aerial_slices.glsl", "sky_aerial.comp.glsl"}), aerial);
  const std::vector<std::string> sunFiles = withFiles(
      kAtmosphereFiles, {"cloudlut_sampling.glsl", "cloudlut_shading.glsl", "sun_volume.glsl",
                         "sun_volume_chord.glsl", "sun_chord_map.glsl", "cascade_columns.glsl",
                         "sun_volume_sampling.glsl",
                         "sky_aerial_slices.glsl", "sky_shafts.glsl"});
  shaftsProgram_ = linkComputeProgram(gl, withFiles(sunFiles, {"sky_shafts.comp.glsl"}),
                                      aerial + glslDefine("SHAFT_PIECES", kShaftPieces) + SunVolume::samplingDefines());
  compositeProgram_ = linkComputeProgram(gl, withFiles(sunFiles, {"sky_composite.comp.glsl"}),
                                         aerial + SunVolume::samplingDefines());
  skyView_ = createFloatTexture3D(gl, context, "the sky view", kSkyViewWidth, kSkyViewHeight, 1, 4, nullptr);
  aerialInScatter_ = createFloatTexture3D(gl, context, "the aerial perspective", kAerialSize, kAerialSize, kAerialSlices, 4, nullptr);
  aerialTransmittance_ = createFloatTexture3D(gl, context, "the aerial perspective", kAerialSize, kAerialSize, kAerialSlices, 4, nullptr);
  aerialSingle_ = createFloatTexture3D(gl, context, "the aerial perspective", kAerialSize, kAerialSize, kAerialSlices, 4, nullptr);
  checkGlError(gl, "creating the sky pass");
}

SkyPass::~SkyPass() {
  for (GLuint* t : {&transmittanceTexture_, &multipleTexture_, &irradianceTexture_, &skyView_, &aerialInScatter_,
                    &aerialTransmittance_, &aerialSingle_, &shaftLoss_})
    deleteTexture(gl_, *t);
}

void SkyPass::setTables(const glsl::AtmosphereParameters& atmosphere, const Table4D& transmittance,
                        const Table4D& multipleScattering, const Table4D& irradiance) {
  for (const Table4D* t : {&transmittance, &multipleScattering, &irradiance})
    if (t->channelCount() != 3 || t->dims()[2] != (t == &multipleScattering ? glsl::CLOUDLUT_MULTIPLE_BLOCKS : 1) ||
        t->dims()[3] != 1)
      throw UsageError("table '" + t->name() + "' is not this version's atmosphere table (3 channels, 2 axes, " +
                       (t == &multipleScattering ? std::to_string(glsl::CLOUDLUT_MULTIPLE_BLOCKS) + " blocks)" : "1 block)"));
  atmosphere_ = atmosphere;
  transmittance_ = transmittance;
  multiple_ = multipleScattering;
  irradiance_ = irradiance;
  for (GLuint* t : {&transmittanceTexture_, &multipleTexture_, &irradianceTexture_}) deleteTexture(gl_, *t);
  transmittanceTexture_ = uploadTable(gl_, context_, transmittance_);
  multipleTexture_ = uploadTable(gl_, context_, multiple_);
  irradianceTexture_ = uploadTable(gl_, context_, irradiance_);
  checkGlError(gl_, "uploading the atmosphere's tables");
}

scene::Lighting SkyPass::cloudLighting(const scene::Lighting& lighting, float altitude) const {
  const auto texture = [](const Table4D& t) { return glsl::AtmosphereTexture{t.data().data(), t.dims()[0], t.dims()[1]}; };
  const float r = atmosphere_.bottomRadius + std::max(altitude, 0.0f);
  const float muS = glm::normalize(lighting.sunDirection).y;
  scene::Lighting out = lighting;
  out.sunColor = lighting.sunColor *
                 glsl::transmittanceToSun(atmosphere_, texture(transmittance_), r, muS, glsl::CLOUDLUT_SUN_ANGULAR_RADIUS);
  out.skyColor = lighting.sunColor * glsl::skyIrradianceLookup(atmosphere_, texture(irradiance_), r, muS) *
                 (4.0f * glsl::CLOUDLUT_INV_4PI);
  // Below the horizon the ground returns its albedo times the sky's irradiance (Lambertian:
  // radiance albedo·E/π, so albedo times skyColor); its return of direct sunlight is left out.
  out.skyBelow = atmosphere_.groundAlbedo;
  return out;
}

void SkyPass::setCommonUniforms(const ProgramUniforms& u, const RenderSettings& s) const {
  const glsl::AtmosphereParameters& a = atmosphere_;
  u.set("uAtmosphere.bottomRadius", a.bottomRadius);
  u.set("uAtmosphere.topRadius", a.topRadius);
  u.set("uAtmosphere.rayleighScattering", a.rayleighScattering);
  u.set("uAtmosphere.rayleighScaleHeight", a.rayleighScaleHeight);
  u.set("uAtmosphere.mieScattering", a.mieScattering);
  u.set("uAtmosphere.mieAbsorption", a.mieAbsorption);
  u.set("uAtmosphere.mieScaleHeight", a.mieScaleHeight);
  u.set("uAtmosphere.mieG", a.mieG);
  u.set("uAtmosphere.ozoneAbsorption", a.ozoneAbsorption);
  u.set("uAtmosphere.ozoneBottom", a.ozoneBottom);
  u.set("uAtmosphere.ozonePeak", a.ozonePeak);
  u.set("uAtmosphere.ozoneTop", a.ozoneTop);
  u.set("uAtmosphere.groundAlbedo", a.groundAlbedo);
  bindTexture3D(gl_, u, "uTransmittance", kTransmittanceUnit, transmittanceTexture_);
  bindTexture3D(gl_, u, "uMultiple", kMultipleUnit, multipleTexture_);
  bindTexture3D(gl_, u, "uIrradiance", kIrradianceUnit, irradianceTexture_);
  const glm::vec3 eye = s.view.camera.eye;
  u.set("uEyeWorld", eye);
  // the camera never below the ground (the scene's rules), nor above the top for the tables
  glm::vec3 eyePlanet = eye - glsl::atmosphereCentre(a);
  const float r = glm::length(eyePlanet);
  eyePlanet *= glm::clamp(r, a.bottomRadius + 1.0f, a.topRadius - 1.0f) / r;
  u.set("uEyePlanet", eyePlanet);
  u.set("uSun", glm::normalize(s.view.lighting.sunDirection));
  u.set("uMsWeight", s.skyOrders == 1 ? 0.0f : 1.0f);
  const scene::CameraFrame frame(s.view.camera, s.width, s.height);
  const float tanHalf = std::tan(0.5f * glm::radians(s.view.camera.fovDeg));
  const float aspect = static_cast<float>(s.width) / static_cast<float>(s.height);
  const glm::vec3 forward = frame.forward();
  const glm::vec3 right = glm::normalize(glm::cross(forward, s.view.camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  u.set("uForward", forward);
  u.set("uRight", right * (tanHalf * aspect));
  u.set("uUp", up * tanHalf);
}

void SkyPass::composite(Image& image, const RenderSettings& s, const SunVolume& sun, bool sunBuilt, float laterAsymmetry) {
  if (!hasTables()) throw std::logic_error("SkyPass::composite before setTables");
  const std::size_t pixels = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  GLint64 maxBlock = 0;
  gl_.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &maxBlock);
  if (static_cast<GLint64>(pixels * 16) > maxBlock)
    throw UsageError("image size " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " exceeds what this OpenGL's sky pass holds (" + std::to_string(maxBlock / 16) + " pixels)");

  // 1. the sky view
  gl_.UseProgram(viewProgram_.id());
  {
    const ProgramUniforms u(gl_, viewProgram_.id());
    setCommonUniforms(u, s);
    gl_.BindImageTexture(0, skyView_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl_.DispatchCompute(groupsFor(kSkyViewWidth, kTileGroup), groupsFor(kSkyViewHeight, kTileGroup), 1);
  }
  // 2. the aerial perspective
  gl_.UseProgram(aerialProgram_.id());
  {
    const ProgramUniforms u(gl_, aerialProgram_.id());
    setCommonUniforms(u, s);
    u.set("uAerialMax", kAerialMaxMetres);
    gl_.BindImageTexture(0, aerialInScatter_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl_.BindImageTexture(1, aerialTransmittance_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl_.BindImageTexture(2, aerialSingle_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl_.DispatchCompute(groupsFor(kAerialSize, kTileGroup), groupsFor(kAerialSize, kTileGroup), 1);
  }
  fullBarrier(gl_);
  // 3. the light shafts' loss, per screen cell
  const bool shafts = s.lightShafts && sunBuilt;
  if (shafts) {
    const glm::ivec2 cells((image.width + kShaftCell - 1) / kShaftCell, (image.height + kShaftCell - 1) / kShaftCell);
    if (cells != shaftCells_) {
      deleteTexture(gl_, shaftLoss_);
      shaftLoss_ = createFloatTexture3D(gl_, context_, "the light shafts", cells.x, cells.y, kAerialSlices, 4, nullptr);
      shaftCells_ = cells;
    }
    gl_.UseProgram(shaftsProgram_.id());
    const ProgramUniforms u(gl_, shaftsProgram_.id());
    setCommonUniforms(u, s);
    u.set("uAerialMax", kAerialMaxMetres);
    u.set("uLaterAsymmetry", laterAsymmetry);
    bindTexture3D(gl_, u, "uAerialSingle", kAerialSingleUnit, aerialSingle_);
    sun.bind(u, kSunVolumeUnit);
    gl_.BindImageTexture(0, shaftLoss_, 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(cells.x), kTileGroup),
                        groupsFor(static_cast<std::size_t>(cells.y), kTileGroup), 1);
    fullBarrier(gl_);
  }
  // 4. the composite, in place on the image's buffers
  colour_.assign(image.rgba.data(), pixels * 16);
  distance_.assign(image.distance.data(), pixels * 4);
  gl_.UseProgram(compositeProgram_.id());
  {
    const ProgramUniforms u(gl_, compositeProgram_.id());
    setCommonUniforms(u, s);
    bindTexture3D(gl_, u, "uSkyView", kSkyViewUnit, skyView_);
    bindTexture3D(gl_, u, "uAerialInScatter", kAerialInScatterUnit, aerialInScatter_);
    bindTexture3D(gl_, u, "uAerialTransmittance", kAerialTransmittanceUnit, aerialTransmittance_);
    bindTexture3D(gl_, u, "uShaftLoss", kShaftLossUnit, shaftLoss_);
    u.set("uShafts", shafts ? 1 : 0);
    u.set("uAerialMax", kAerialMaxMetres);
    gl_.Uniform2i(u.location("uSize"), image.width, image.height);
    u.set("uFirstRow", 0);
    u.set("uNoDistance", kNoDistance);
    u.set("uLaterAsymmetry", laterAsymmetry);
    sun.bind(u, kSunVolumeUnit);
    if (!sunBuilt) u.set("uSunCascades", 0);
    colour_.bind(kColourBinding);
    distance_.bind(kDistanceBinding);
    gl_.DispatchCompute(groupsFor(static_cast<std::size_t>(image.width), kCompositeGroup),
                        static_cast<GLuint>(image.height), 1);
  }
  fullBarrier(gl_);
  colour_.read(0, pixels * 16, image.rgba.data());
  checkGlError(gl_, "compositing the sky");
}

}  // namespace cloudlut::render
