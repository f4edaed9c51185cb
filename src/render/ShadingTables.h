#pragma once
// The three tables the particle pass shades with (seed §4.4), as 3D textures in their file
// layout (axes 0, 1 and 2·3 folded into one: texel (i0, i1, i2 + N2·i3)); the optical-depth
// texture carries a third channel, the last matter derived from the file's two
// (LastMatterTexture.h). With the parameters the shader needs to address and decode them: the
// optical-depth table's unit optical radius
// σ = extinction_per_m · radius_m, the scattering tables' density axis (log2 ρ at its ends) and θS
// warp, and the single table's first phase function.
#include <string>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "core/AngularClosure.h"
#include "io/LutIo.h"
#include "render/GlContext.h"
#include "render/GlFunctions.h"
#include "render/GlResources.h"
#include "render/SplatTable.h"

namespace cloudlut::render {

class ShadingTables {
 public:
  // Uses the set's "optical_depth", "single_scattering" (log2 mean source) and
  // "multiple_scattering" (mean source) tables, and the multiple table's "angular_closure" when it
  // has one; FileError naming the directory when one is missing or unusable (storage, channels,
  // payload size, non-finite values, first_phase, angular_closure, chord_outer_third_share).
  ShadingTables(const GlFunctions& gl, const GlContext& context, const io::LutSet& luts);
  ~ShadingTables();
  ShadingTables(const ShadingTables&) = delete;
  ShadingTables& operator=(const ShadingTables&) = delete;

  float unitOpticalRadius() const { return unitOpticalRadius_; }
  // Radius R of the optical-depth table's reference particle (its radius_m), m.
  float referenceRadius() const { return referenceRadius_; }
  // Mean cosine ∫ μ P(μ) dω of the multiple table's later phase function (its `later_phase`;
  // dimensionless): the asymmetry of the light's diffuse transport between particles.
  float laterPhaseAsymmetry() const { return laterAsymmetry_; }
  // The optical-depth table for the sun and zenith volumes' splat, with its
  // chord_outer_third_share (1/3 when the table records none).
  SplatTable splatTable() const { return {opticalDepth_.texture, opticalDepth_.dims, unitOpticalRadius_, chordOuterThird_}; }

  // Binds the tables to texture units 0 to 2 and sets the particle program's uniforms that
  // describe them (uOpticalDepth*, uSingle*, uMultiple*, uUnitOpticalRadius, uFirstPhase*,
  // uLaterAsymmetry, uAngularClosure*).
  void bind(const ProgramUniforms& uniforms) const;

 private:
  struct Texture {
    GLuint texture = 0;
    glm::vec4 dims{0.0f};
    glm::vec4 scatteringAxes{0.0f};  // scattering table: scatteringAxesRecord (core/TableLookup.h)
  };
  // the optical-depth table gets its last matter derived (LastMatterTexture.h); a scattering
  // table its density axis record
  enum class TableKind { OpticalDepth, Scattering };
  Texture upload(const GlContext& context, const Table4D& table, TableKind kind);
  // Validates and keeps the multiple table's "angular_closure" record (FileError naming the field).
  void readAngularClosure(const nlohmann::json& record);
  void bindTable(const ProgramUniforms& uniforms, int unit, const char* sampler, const char* dimsName,
                 const Texture& t) const;

  const GlFunctions& gl_;
  std::string luts_;
  Texture opticalDepth_, single_, multiple_;
  float unitOpticalRadius_ = 0;
  float referenceRadius_ = 0;
  float chordOuterThird_ = 1.0f / 3.0f;
  int firstPhaseKind_ = 2;
  float firstPhaseParam_ = 0.9f;
  float laterAsymmetry_ = 0.0f;
  // the multiple table's angular closure K(ρ, μ) (core/AngularClosure.h); its default, one node
  // and one bin of 1, when the table has none
  AngularClosure closure_;
};

}  // namespace cloudlut::render
