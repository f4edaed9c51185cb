#pragma once
// A LUT set baked into a directory, what `cloudlut bake` runs: the optical-depth table of the
// reference particle and the scattering tables of the homogeneous sphere, each written in the
// chosen formats (io/ManifestSchema.h), then manifest.json last, into a staging directory that
// replaces the LUT directory in one step at the end (io/LutSetTransaction.h): an interrupted
// bake leaves the old set or the new one, never a mix. With a scene (--for-scene) the resolutions are chosen
// first (bake/ResolutionChoice.h) and the choice is recorded in the manifest's "for_scene".
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "bake/AngularClosureBaker.h"
#include "bake/AtmosphereBaker.h"
#include "bake/OpticalDepthBaker.h"
#include "bake/ResolutionChoice.h"
#include "bake/ScatteringBaker.h"
#include "core/Progress.h"
#include "io/ManifestSchema.h"

namespace cloudlut::bake {

struct LutSetPlan {
  std::filesystem::path out;  // the LUT directory (its parent must exist and be writable)
  bool opticalDepth = true;   // bake the optical-depth table
  OpticalDepthSettings od;
  ScatteringSettings sc;      // sc.single / sc.multiple: which scattering tables to bake
  // With the optical-depth and multiple tables baked together, the multiple table carries the
  // angular closure of the particle's own term (bake/AngularClosure.h) in its parameters.
  bool angularClosure = true;
  AngularClosureSettings closure;
  DensityModel model = DensityModel::Noise;
  std::uint64_t seed = 1;
  io::TableFormats formats;
  io::SampleType precision = io::SampleType::Half;  // u8 for the optical-depth table only
  std::string generator;      // the manifest's "generator", e.g. "cloudlut 0.1.0"
  std::optional<SceneNeeds> forScene;  // choose the resolutions for this scene
  double tolerance = 0.01;             // ... within this 95th-percentile error
  bool atmosphere = false;    // bake the atmosphere's tables (bake/AtmosphereBaker.h)
  glsl::AtmosphereParameters atmosphereParameters = glsl::defaultAtmosphere();
  bool scattering() const { return sc.single || sc.multiple; }
};

// Bakes and writes the plan's tables, then the manifest (format, version, generator,
// "parameters" {extinction_per_m, radius_m, density_model, seed, orders, method},
// "scattering_report", "bake_seconds", "for_scene", "tables"; with the atmosphere, "atmosphere"
// holds its parameters), and returns the manifest. With
// a scene, plan.od.dims and plan.sc.dims become the chosen resolutions. `stageDone` is called
// after each table's bake (a progress bar ends its line there).
nlohmann::json bakeLutSet(LutSetPlan& plan, const ProgressFn& progress = {},
                          const std::function<void()>& stageDone = {});

// What --for-scene skipped and saved against the default bake (64×32×64×32 optical depth,
// 32×64×16×8 scattering): the scene's density range, the chosen resolutions and their errors
// against the tolerance, and the megabytes and (estimated) seconds saved. Lines of text.
std::string forSceneSummary(const LutSetPlan& plan, const nlohmann::json& manifest);

}  // namespace cloudlut::bake
