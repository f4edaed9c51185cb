// The volume resolve's sorting networks (render/SortingNetwork.h) against what a sorting network
// must do: by the 0–1 principle a comparator network sorts every input if and only if it sorts
// every sequence of zeros and ones, so the 16-element network is checked on all 2^16 of them;
// the 32- and 64-element ones (the resolve of 16 and 32 segments) on random 0–1 sequences and on
// random reals against std::sort.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "core/Errors.h"
#include "render/SortingNetwork.h"

using namespace cloudlut;
using namespace cloudlut::render;

namespace {

template <typename T>
void sortWith(const std::vector<CompareExchange>& network, std::vector<T>& v) {
  for (const auto& [i, j] : network)
    if (v[static_cast<std::size_t>(j)] < v[static_cast<std::size_t>(i)])
      std::swap(v[static_cast<std::size_t>(i)], v[static_cast<std::size_t>(j)]);
}

// How many of the 2^16 sequences of zeros and ones of 16 elements the network leaves unsorted.
int unsortedBinary16(const std::vector<CompareExchange>& network) {
  int unsorted = 0;
  for (std::uint32_t bits = 0; bits < (1u << 16); ++bits) {
    std::vector<int> v(16);
    for (int k = 0; k < 16; ++k) v[static_cast<std::size_t>(k)] = static_cast<int>((bits >> k) & 1u);
    sortWith(network, v);
    unsorted += std::is_sorted(v.begin(), v.end()) ? 0 : 1;
  }
  return unsorted;
}

}  // namespace

TEST_CASE("sorting network: Batcher's odd-even merge sort sorts every input", "[render][network]") {
  const auto n16 = oddEvenMergeSortNetwork(16);
  const auto n32 = oddEvenMergeSortNetwork(32);
  const auto n64 = oddEvenMergeSortNetwork(64);
  CHECK(n16.size() == 63);  // n/4 · log2 n · (log2 n − 1) + n − 1
  CHECK(n32.size() == 191);
  CHECK(n64.size() == 543);
  for (const auto& [i, j] : n64) {
    CHECK(i < j);
    CHECK(j < 64);
  }
  CHECK(unsortedBinary16(n16) == 0);
  int unsorted = 0;
  std::mt19937 rng(7);
  for (const auto* network : {&n32, &n64}) {
    const std::size_t n = network == &n32 ? 32 : 64;
    for (int trial = 0; trial < 20000; ++trial) {
      std::vector<int> bits(n);
      for (int& b : bits) b = static_cast<int>(rng() & 1u);
      sortWith(*network, bits);
      unsorted += std::is_sorted(bits.begin(), bits.end()) ? 0 : 1;
      std::vector<float> reals(n);
      for (float& x : reals) x = static_cast<float>(rng() % 1000u);  // with ties
      std::vector<float> expected = reals;
      std::sort(expected.begin(), expected.end());
      sortWith(*network, reals);
      unsorted += reals == expected ? 0 : 1;
    }
  }
  CHECK(unsorted == 0);

  // A network with one compare-exchange left out fails the check above.
  auto broken = n16;
  broken.erase(broken.begin() + 40);
  CHECK(unsortedBinary16(broken) > 0);

  CHECK(networkGlsl(std::vector<CompareExchange>{{0, 1}, {2, 3}}) == "CX(0, 1); CX(2, 3); ");
  CHECK_THROWS_AS(oddEvenMergeSortNetwork(12), UsageError);
  CHECK_THROWS_AS(oddEvenMergeSortNetwork(1), UsageError);
}
