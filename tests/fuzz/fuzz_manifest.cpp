// Fuzzes manifest.json: the input replaces the manifest of a directory holding the valid table
// that the seed manifest describes, so mutated manifests reach the table-loading and
// cross-checking code, not only the JSON parser.
#include <exception>
#include <filesystem>

#include "FuzzFile.h"
#include "io/LutIo.h"

namespace {
const bool kTableCopied = [] {
  std::filesystem::copy_file(CLOUDLUT_FUZZ_SEED_BIN, cloudlut::fuzz::scratchDir() / "optical_depth.bin",
                             std::filesystem::copy_options::overwrite_existing);
  return true;
}();
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)kTableCopied;
  cloudlut::fuzz::writeScratch("manifest.json", data, size);
  try {
    (void)cloudlut::io::readLutSet(cloudlut::fuzz::scratchDir());
  } catch (const std::exception&) {
  }
  return 0;
}
