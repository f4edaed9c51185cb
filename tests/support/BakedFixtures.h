#pragma once
// The expensive fixtures of the scattering tests: the default bake (ScatteringSettings{} with
// a given number of orders), baked once per test run.
//
// catch_discover_tests runs every test case in a process of its own, so a static cache alone
// would re-bake a fixture in every test case that needs it. Under ctest the environment
// variable CLOUDLUT_TEST_FIXTURE_DIR (set in tests/CMakeLists.txt, emptied at the start and
// the end of every ctest run) names a directory where the first process to need a fixture
// bakes it, under a lock, and writes it atomically (float binary tables, bit-exact, plus the
// bake report); later processes read it back. Without the variable (the test binary run by
// hand) each process bakes its own, once.
#include "bake/ScatteringBaker.h"

namespace cloudlut::test {

// bake::bakeScattering of the default settings with `orders` orders (0 = converged). The
// reference stays valid until the process ends.
const bake::ScatteringResult& defaultScattering(int orders);

}  // namespace cloudlut::test
