// Inputs the fuzzers found (tests/fuzz/regressions): each must be rejected with a FileError,
// cheaply, by the reader it was found against.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/Errors.h"
#include "io/LutIo.h"

using namespace cloudlut;

TEST_CASE("fuzzer-found inputs are rejected cleanly", "[io][fuzz]") {
  const std::filesystem::path dir = std::filesystem::path(CLOUDLUT_SOURCE_DIR) / "tests" / "fuzz" / "regressions";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    INFO(entry.path().string());
    CHECK_THROWS_AS(io::readLut(entry.path()), FileError);
    ++count;
  }
  CHECK(count >= 1);
}
