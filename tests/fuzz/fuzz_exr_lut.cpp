// Fuzzes the EXR LUT reader (OpenEXR underneath): load or throw, never crash.
#include <exception>

#include "FuzzFile.h"
#include "io/LutReaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cloudlut::fuzz::writeScratch("lut.exr", data, size);
  try {
    (void)cloudlut::io::readExrLut(path);
  } catch (const std::exception&) {
  }
  return 0;
}
