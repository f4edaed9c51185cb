#pragma once
// Assertion helpers: the message of an expected exception, and bit-for-bit float equality.
#include <catch2/catch.hpp>

#include <cstring>
#include <stdexcept>
#include <string>

#include "core/Errors.h"

namespace cloudlut::test {

// The message of the `Error` that f() throws; fails the test if it throws anything else or
// nothing.
template <typename Error, typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  FAIL("expected an exception of the expected type");
  return {};
}

template <typename F>
std::string fileErrorOf(F&& f) {
  return errorOf<cloudlut::FileError>(f);
}

template <typename F>
std::string runtimeErrorOf(F&& f) {
  return errorOf<std::runtime_error>(f);
}

// True if a and b have the same bits (distinguishes −0 from 0, matches NaN payloads).
inline bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace cloudlut::test
