// Fuzzes the geometry CSV read by `query` and `reference sphere`.
#include <exception>

#include "FuzzFile.h"
#include "io/QueryCsv.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = cloudlut::fuzz::writeScratch("query.csv", data, size);
  try {
    (void)cloudlut::io::readQueryCsv(path);
  } catch (const std::exception&) {
  }
  return 0;
}
