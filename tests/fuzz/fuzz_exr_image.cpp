// Fuzzes the EXR image reader of `cloudlut compare` (io/ExrImage, OpenEXR underneath): load or
// throw, never crash, never allocate more than the file's size can justify (io/ExrBudget.h).
#include <exception>

#include "FuzzFile.h"
#include "io/ExrImage.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cloudlut::fuzz::writeScratch("image.exr", data, size);
  try {
    (void)cloudlut::io::readExrImage(path);
  } catch (const std::exception&) {
  }
  return 0;
}
