// Input for flux_limited_diffusion.py (a research prototype, not built by CMake or CI):
//   prototype_io density OUT.raw          the default noise particle's normalised density ρ̂ at
//                                         128³ cell centres of [−1, 1]³ (float32, x fastest)
//   prototype_io channels IN.exr OUT.raw CH...   the named channels of an EXR, as int32 width,
//                                         height, then float32 per pixel, channels interleaved
// Build from the repository root after a release build:
//   g++ -O2 -std=c++20 -Isrc -Ilut_formats -I/usr/include/eigen3 -I/usr/include/OpenEXR
//       -I/usr/include/Imath scripts/prototypes/prototype_io.cpp build/libcloudlut_core.a
//       -lOpenEXR -lImath -ltbb -o build/prototype_io        (one line)
#include <ImfArray.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <vector>

#include "core/Medium.h"
#include "core/ReferenceParticle.h"

namespace {

int density(const char* out) {
  const cloudlut::Medium medium;
  const cloudlut::ReferenceParticle particle(medium.model, medium.seed);
  const int n = 128;
  std::vector<float> v(static_cast<std::size_t>(n) * n * n);
  const auto at = [n](int i) { return -1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(n); };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v[(static_cast<std::size_t>(k) * n + j) * n + i] = particle.density({at(i), at(j), at(k)});
  std::ofstream(out, std::ios::binary).write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * 4));
  return 0;
}

int channels(const char* in, const char* out, int count, char** names) {
  Imf::InputFile file(in);
  const auto dw = file.header().dataWindow();
  const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  std::vector<std::vector<float>> data(count, std::vector<float>(static_cast<std::size_t>(w) * h));
  Imf::FrameBuffer fb;
  for (int c = 0; c < count; ++c)
    fb.insert(names[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data[c].data() - dw.min.x - dw.min.y * w), 4, 4 * w));
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  std::ofstream f(out, std::ios::binary);
  f.write(reinterpret_cast<const char*>(&w), 4).write(reinterpret_cast<const char*>(&h), 4);
  const std::size_t pixels = static_cast<std::size_t>(w) * h;
  for (std::size_t p = 0; p < pixels; ++p)
    for (int c = 0; c < count; ++c) f.write(reinterpret_cast<const char*>(&data[c][p]), 4);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "density") == 0) return density(argv[2]);
  if (argc >= 5 && std::strcmp(argv[1], "channels") == 0) return channels(argv[2], argv[3], argc - 4, argv + 4);
  std::fprintf(stderr, "usage: prototype_io density OUT.raw | prototype_io channels IN.exr OUT.raw CH...\n");
  return 2;
}
