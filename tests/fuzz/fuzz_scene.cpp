// Fuzzes the particle / scene JSON reader.
#include <exception>

#include "FuzzFile.h"
#include "scene/Scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cloudlut::fuzz::writeScratch("scene.json", data, size);
  try {
    (void)cloudlut::scene::readScene(path);
  } catch (const std::exception&) {
  }
  return 0;
}
