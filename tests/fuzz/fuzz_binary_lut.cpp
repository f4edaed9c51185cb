// Fuzzes the binary LUT reader: any input must load or throw FileError, never crash.
#include <exception>

#include "FuzzFile.h"
#include "io/LutReaders.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cloudlut::fuzz::writeScratch("lut.bin", data, size);
  try {
    (void)cloudlut::io::readBinaryLut(path);
  } catch (const std::exception&) {
  }
  return 0;
}
