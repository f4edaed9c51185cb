#pragma once
// The angular closure K(ρ, μ) of a particle's own multiple-scattering term (docs/LIGHTING.md, "The
// particle's own term, closed per exit direction"): the factor by which the renderer scales the
// light the own-term model sends toward exit direction μ = ω_out · l (l toward the sun) from a
// particle of density scale ρ, so that it sends what the reference particle does. Computed by
// the baker (bake/AngularClosureBaker.h) and carried by the multiple table in its parameters under
// "angular_closure" (lut_formats/FORMAT.md); particle.frag.glsl's angularClosure() reads it.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cloudlut {

// Largest number of density nodes or μ bins a closure may have (the shader's uniform array holds
// kMaxAngularClosureAxis² values).
inline constexpr int kMaxAngularClosureAxis = 16;

struct AngularClosure {
  float log2RhoFirst = 0.0f;          // log2 ρ of the first density node
  float log2RhoStep = 1.0f;           // node spacing, octaves (> 0)
  int densityNodes = 1, muBins = 1;   // each 1 … kMaxAngularClosureAxis
  std::vector<float> values{1.0f};    // K (dimensionless), [node · muBins + bin], each in [1/4, 4]
  std::vector<float> relativeErrors;  // the Monte Carlo's relative standard error of each K, or empty
  // K closes the own term darkened by its core shadow (ownCoreShadow, cloudlut_shading.glsl), so
  // the renderer applies that factor; false for sets baked before it, whose K closes the term
  // without it.
  bool ownCoreShadow = false;
  // The most that factor may brighten the term (≥ 1; 1 for sets baked before the bound was
  // raised: they never brighten).
  float ownCoreShadowMax = 1.0f;
};

// Largest own_core_shadow_max a record may hold.
inline constexpr float kMaxOwnCoreShadowMax = 4.0f;

// The record: {"log2_rho_first", "log2_rho_step", "density_nodes", "mu_bins", "values",
// "relative_errors", "own_core_shadow", "own_core_shadow_max"} (own_core_shadow a boolean, false
// when absent; own_core_shadow_max a number in [1, kMaxOwnCoreShadowMax], 1 when absent).
nlohmann::json angularClosureToJson(const AngularClosure& closure);

// The closure a record describes, or nullopt with `problem` saying which field is wrong and why.
std::optional<AngularClosure> angularClosureFromJson(const nlohmann::json& record, std::string& problem);

// K at density scale ρ and exit direction μ ∈ [−1, 1]: linear in log2 ρ between the nodes and in μ
// between the bins' centres, held beyond the first and last: the shared GLSL's
// angularClosurePosition, angularClosureCell and angularClosureBlend (cloudlut_shading.glsl),
// which the particle shader's angularClosure() calls too.
float angularClosureAt(const AngularClosure& closure, float rho, float mu);

}  // namespace cloudlut
