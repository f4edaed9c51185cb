// sample_lut: load a cloudlut LUT set and evaluate its tables for one view ray, as an engine's
// CPU code would (the shaders do the same with cloudlut_sampling.glsl).
//   usage: sample_lut LUT_DIR [density]
// The ray enters the particle (the unit sphere) at S and travels along v; l points to the sun.
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>

#include <cloudlut_glsl.hpp>      // the shaders' parameterization and shading, compiled through GLM
#include <cloudlut_lut.h>         // header-only, dependency-free reader of the binary tables
#include <cloudlut_manifest.h>    // optional: manifest.json and the tables' JSON descriptions

namespace {

bool exists(const std::string& path) { return std::ifstream(path).good(); }

// A number from the table's header description, e.g. ("parameters", "first_phase", "kind").
double described(const cloudlut_reader::Lut& lut, const char* a, const char* b, const char* c, double fallback) {
  const cloudlut_reader::Json d = cloudlut_reader::parseDescription(lut);
  const cloudlut_reader::Json* j = d.find(a);
  if (j && b) j = j->find(b);
  if (j && c) j = j->find(c);
  return j && j->type == cloudlut_reader::Json::Type::Number ? j->number : fallback;
}

// Samples a scattering table (θS, φv, θv, log2 ρ) at the ray: axis fractions from the shared
// GLSL, with the file's axes record (density range, θS node concentration "warp", and the
// layout: φv folded onto [0, π], density interpolated linearly in ρ) and density node count.
float sampleScattering(const cloudlut_reader::Lut& t, glm::vec3 S, glm::vec3 v, glm::vec3 l, float rho) {
  const std::array<float, 4> a = t.scatteringAxesRecord();
  const glm::vec4 x = cloudlut::glsl::scatteringAxes(S, v, l, rho, glm::vec4(a[0], a[1], a[2], a[3]),
                                                     static_cast<float>(t.dims[3]));
  float value = 0.0f;
  t.sample(x.x, x.y, x.z, x.w, &value);
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: sample_lut LUT_DIR [density]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const float rho = argc > 2 ? std::strtof(argv[2], nullptr) : 1.0f;
  try {
    namespace glsl = cloudlut::glsl;
    const cloudlut_reader::Manifest manifest = cloudlut_reader::readManifest(dir);
    const glm::vec3 S = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    const glm::vec3 v = glm::normalize(-S + glm::vec3(0.2f, 0.1f, 0.0f));
    const glm::vec3 l = glm::normalize(glm::vec3(0.2f, 0.9f, 0.4f));
    // σ = β·R, the optical radius of a particle of density scale 1, from the bake's parameters
    const cloudlut_reader::Json* params = manifest.document.find("parameters");
    const cloudlut_reader::Json* beta = params ? params->find("extinction_per_m") : nullptr;
    const cloudlut_reader::Json* radius = params ? params->find("radius_m") : nullptr;
    const float sigma = static_cast<float>((beta ? beta->number : 0.07) * (radius ? radius->number : 183.8));
    const float chord = glsl::chordLength(S, v);
    std::printf("tables %zu\n", manifest.tables.size());

    if (exists(dir + "/optical_depth.bin")) {
      const cloudlut_reader::Lut od = cloudlut_reader::readLut(dir + "/optical_depth.bin");
      const glm::vec4 x = glsl::opticalDepthAxes(S, v);  // axis fractions in [0, 1]
      float value[2] = {0.0f, 0.0f};
      od.sample(x.x, x.y, x.z, x.w, value);
      const float tau = glsl::particleOpticalDepth(rho, sigma, chord, value[0]);
      std::printf("optical_depth %ux%ux%ux%u: mean_density %.6f first_matter %.6f optical_depth %.6f transmittance %.6f\n",
                  od.dims[0], od.dims[1], od.dims[2], od.dims[3], value[0], value[1], tau, std::exp(-tau));
    }
    // The homogeneous sphere of density ρ (what `cloudlut query` prints): τ = ρ·σ·chord. In a
    // renderer τ is the particle's optical depth along the ray, and the single table is read
    // at ρ times the ray's mean density (docs/ENGINE_GUIDE.md §5).
    const float tauSphere = rho * sigma * chord;
    if (exists(dir + "/single_scattering.bin")) {
      const cloudlut_reader::Lut l1 = cloudlut_reader::readLut(dir + "/single_scattering.bin");
      const int kind = static_cast<int>(described(l1, "parameters", "first_phase", "kind", 2));
      const float param = static_cast<float>(described(l1, "parameters", "first_phase", "param", 0.9));
      const float phase = glsl::phaseFunction(kind, glm::dot(v, l), param);
      std::printf("single %.6g\n", phase * glsl::singleScatteringFromTable(sampleScattering(l1, S, v, l, rho), tauSphere));
    }
    if (exists(dir + "/multiple_scattering.bin")) {
      const cloudlut_reader::Lut lm = cloudlut_reader::readLut(dir + "/multiple_scattering.bin");
      std::printf("multiple %.6g\n", glsl::multipleScatteringFromTable(sampleScattering(lm, S, v, l, rho), tauSphere));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sample_lut: %s\n", e.what());
    return 1;
  }
  return 0;
}
