#include "render/ShadingTables.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/Errors.h"
#include "core/Defaults.h"
#include "core/Phase.h"
#include "core/TableLookup.h"
#include "render/LastMatterTexture.h"

namespace cloudlut::render {

static_assert(kMaxAngularClosureAxis * kMaxAngularClosureAxis == 256,
              "particle.frag.glsl declares uAngularClosure[256]");

namespace {

const Table4D& requireTable(const io::LutSet& luts, const std::string& name) {
  const auto it = luts.tables.find(name);
  if (it == luts.tables.end())
    throw FileError(luts.dir.string(), "has no '" + name + "' table (the renderer needs optical_depth, "
                                       "single_scattering and multiple_scattering)");
  return it->second.table;
}

}  // namespace

ShadingTables::ShadingTables(const GlFunctions& gl, const GlContext& context, const io::LutSet& set)
    : gl_(gl), luts_(set.dir.string()) {
  const Table4D& od = requireTable(set, "optical_depth");
  const Table4D& l1 = requireTable(set, "single_scattering");
  const Table4D& lm = requireTable(set, "multiple_scattering");
  // the shader decodes single_scattering as log2 and multiple_scattering as linear mean sources
  ScatteringStorage storage1, storageM;
  try {
    storage1 = scatteringStorage(l1);
    storageM = scatteringStorage(lm);
  } catch (const std::runtime_error& e) {
    throw FileError(luts_, e.what());
  }
  if (storage1 != ScatteringStorage::Log2MeanSource || storageM != ScatteringStorage::MeanSource)
    throw FileError(luts_, std::string("single_scattering must store '") + kSingleScatteringChannel +
                               "' and multiple_scattering '" + kMultipleScatteringChannel + "'");
  unitOpticalRadius_ = cloudlut::unitOpticalRadius(od);
  if (!(unitOpticalRadius_ > 0.0f) || !std::isfinite(unitOpticalRadius_))
    throw FileError(luts_, "optical_depth: extinction_per_m · radius_m is not a positive number");
  referenceRadius_ = static_cast<float>(od.parameters().value("radius_m", defaults::kParticleRadiusMetres));
  if (!(referenceRadius_ > 0.0f) || !std::isfinite(referenceRadius_))
    throw FileError(luts_, "optical_depth: radius_m is not a positive number");
  try {
    chordOuterThird_ = chordOuterThird(od);
  } catch (const std::invalid_argument& e) {
    throw FileError(luts_, std::string("optical_depth: ") + e.what());
  }
  // The phases the tables were baked with (FileError naming the field when malformed); a table
  // that records none was baked with the defaults.
  const auto phaseOf = [&](const Table4D& t, const char* key, const Phase& fallback) {
    const nlohmann::json& params = t.parameters();
    return params.contains(key) ? phaseFromJson(params[key], luts_, t.name() + ": " + key) : fallback;
  };
  const Phase first = phaseOf(l1, "first_phase", defaults::kFirstPhase);
  const Phase later = phaseOf(lm, "later_phase", defaults::kLaterPhase);
  firstPhaseKind_ = glslKind(first.kind);
  firstPhaseParam_ = first.param;
  laterAsymmetry_ = phaseMeanCosine(later);
  if (lm.parameters().contains("angular_closure")) readAngularClosure(lm.parameters()["angular_closure"]);

  try {
    opticalDepth_ = upload(context, od, TableKind::OpticalDepth);
    single_ = upload(context, l1, TableKind::Scattering);
    multiple_ = upload(context, lm, TableKind::Scattering);
  } catch (...) {
    const GLuint textures[] = {opticalDepth_.texture, single_.texture, multiple_.texture};
    gl_.DeleteTextures(3, textures);
    throw;
  }
}

ShadingTables::~ShadingTables() {
  const GLuint textures[] = {opticalDepth_.texture, single_.texture, multiple_.texture};
  gl_.DeleteTextures(3, textures);
}

ShadingTables::Texture ShadingTables::upload(const GlContext& context, const Table4D& table, TableKind kind) {
  const bool scattering = kind == TableKind::Scattering;
  const auto d = table.dims();
  const int channels = table.channelCount();
  if (channels < 1 || channels > 4)
    throw FileError(luts_, table.name() + ": " + std::to_string(channels) + " channels (the renderer takes 1 to 4)");
  if (table.data().size() != table.nodeCount() * static_cast<std::size_t>(channels))
    throw FileError(luts_, table.name() + ": payload size does not match its dimensions");
  for (float v : table.data())
    if (!std::isfinite(v)) throw FileError(luts_, table.name() + ": holds a non-finite value");
  Texture t;
  // the optical-depth table with its last matter derived (LastMatterTexture.h)
  t.texture = scattering ? createFloatTexture3D(gl_, context, table.name(), d[0], d[1],
                                               static_cast<long long>(d[2]) * d[3], channels, table.data().data())
                         : createOpticalDepthTexture(gl_, context, table);
  t.dims = glm::vec4(d[0], d[1], d[2], d[3]);
  if (scattering) {
    t.scatteringAxes = scatteringAxesRecord(table);  // density range, θS warp, layout flags
    if (!std::isfinite(t.scatteringAxes.x) || !std::isfinite(t.scatteringAxes.y)) {
      gl_.DeleteTextures(1, &t.texture);
      throw FileError(luts_, table.name() + ": density axis range is not finite");
    }
  }
  checkGlError(gl_, ("uploading table " + table.name()).c_str());
  return t;
}

void ShadingTables::bindTable(const ProgramUniforms& uniforms, int unit, const char* sampler, const char* dimsName,
                              const Texture& t) const {
  gl_.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
  gl_.BindTexture(GL_TEXTURE_3D, t.texture);
  uniforms.set(sampler, unit);
  uniforms.set(dimsName, t.dims);
}

void ShadingTables::bind(const ProgramUniforms& uniforms) const {
  bindTable(uniforms, 0, "uOpticalDepth", "uOpticalDepthDims", opticalDepth_);
  bindTable(uniforms, 1, "uSingle", "uSingleDims", single_);
  bindTable(uniforms, 2, "uMultiple", "uMultipleDims", multiple_);
  uniforms.set("uSingleAxes", single_.scatteringAxes);
  uniforms.set("uMultipleAxes", multiple_.scatteringAxes);
  uniforms.set("uUnitOpticalRadius", unitOpticalRadius_);
  uniforms.set("uFirstPhaseKind", firstPhaseKind_);
  uniforms.set("uFirstPhaseParam", firstPhaseParam_);
  uniforms.set("uLaterAsymmetry", laterAsymmetry_);
  uniforms.set("uAngularClosureRho", glm::vec4(closure_.log2RhoFirst, closure_.log2RhoStep, 0.0f, 0.0f));
  uniforms.set("uAngularClosureDims", glm::ivec3(closure_.densityNodes, closure_.muBins, closure_.ownCoreShadow ? 1 : 0));
  uniforms.set("uAngularClosure", closure_.values);
  uniforms.set("uOwnCoreShadowMax", closure_.ownCoreShadowMax);
}

void ShadingTables::readAngularClosure(const nlohmann::json& record) {
  std::string problem;
  const std::optional<AngularClosure> closure = angularClosureFromJson(record, problem);
  if (!closure) throw FileError(luts_, "multiple_scattering: parameters.angular_closure: " + problem);
  closure_ = *closure;
}

}  // namespace cloudlut::render
