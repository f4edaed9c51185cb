// sample_lut: load a cloudlut LUT set, sample its optical-depth table for one view ray, print it.
//   usage: sample_lut LUT_DIR [density]
// The ray enters the particle (the unit sphere) at S and travels along v.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include <cloudlut_glsl.hpp>    // the shaders' parameterization, compiled through GLM
#include <cloudlut_reader.h>    // header-only, dependency-free reader

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: sample_lut LUT_DIR [density]\n");
    return 2;
  }
  const float rho = argc > 2 ? std::strtof(argv[2], nullptr) : 1.0f;
  try {
    const cloudlut_reader::Manifest manifest = cloudlut_reader::readManifest(argv[1]);
    const cloudlut_reader::Lut od = cloudlut_reader::readLut(std::string(argv[1]) + "/optical_depth.bin");
    const glm::vec3 S = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
    const glm::vec3 v = glm::normalize(-S + glm::vec3(0.2f, 0.1f, 0.0f));
    const glm::vec4 x = cloudlut::glsl::opticalDepthAxes(S, v);  // axis fractions in [0, 1]
    float value[2] = {0.0f, 0.0f};
    od.sample(x.x, x.y, x.z, x.w, value);
    // σ = β·R, the optical radius of a particle of density scale 1, from the bake's parameters
    const cloudlut_reader::Json* params = manifest.document.find("parameters");
    const cloudlut_reader::Json* beta = params ? params->find("extinction_per_m") : nullptr;
    const cloudlut_reader::Json* radius = params ? params->find("radius_m") : nullptr;
    const float sigma = static_cast<float>((beta ? beta->number : 0.07) * (radius ? radius->number : 183.8));
    const float tau = rho * sigma * cloudlut::glsl::chordLength(S, v) * value[0];
    std::printf("tables %zu, optical_depth %ux%ux%ux%u\n", manifest.tables.size(), od.dims[0], od.dims[1],
                od.dims[2], od.dims[3]);
    std::printf("mean_density %.6f first_matter %.6f optical_depth %.6f transmittance %.6f\n", value[0],
                value[1], tau, std::exp(-tau));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sample_lut: %s\n", e.what());
    return 1;
  }
  return 0;
}
