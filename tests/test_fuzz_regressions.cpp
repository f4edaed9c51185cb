// Inputs the fuzzers found (tests/fuzz/regressions): each must be rejected with a FileError,
// cheaply, by the reader it was found against.
#include <catch2/catch.hpp>

#include <filesystem>

#include "core/Errors.h"
#include "io/ExrImage.h"
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

// And those found against compare's image reader (tests/fuzz/regressions_exr_image), among them
// a header attribute that declared 1.7 GB, which OpenEXR reserved before it found the file short.
TEST_CASE("fuzzer-found EXR images are rejected cleanly", "[io][fuzz]") {
  const std::filesystem::path dir =
      std::filesystem::path(CLOUDLUT_SOURCE_DIR) / "tests" / "fuzz" / "regressions_exr_image";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    INFO(entry.path().string());
    CHECK_THROWS_AS(io::readExrImage(entry.path()), FileError);
    ++count;
  }
  CHECK(count >= 1);
}
