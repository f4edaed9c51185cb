#include "render/SortingNetwork.h"

#include "core/Errors.h"

namespace cloudlut::render {

namespace {

// Merges the two sorted halves of the elements lo, lo + r, lo + 2r, … up to hi (inclusive).
void oddEvenMerge(int lo, int hi, int r, std::vector<CompareExchange>& out) {
  const int step = 2 * r;
  if (step < hi - lo) {
    oddEvenMerge(lo, hi, step, out);      // the even subsequence
    oddEvenMerge(lo + r, hi, step, out);  // the odd one
    for (int i = lo + r; i + r < hi; i += step) out.emplace_back(i, i + r);
  } else {
    out.emplace_back(lo, lo + r);
  }
}

// Sorts the elements lo … hi (inclusive; a power of two of them).
void oddEvenMergeSort(int lo, int hi, std::vector<CompareExchange>& out) {
  if (hi <= lo) return;
  const int mid = lo + (hi - lo) / 2;
  oddEvenMergeSort(lo, mid, out);
  oddEvenMergeSort(mid + 1, hi, out);
  oddEvenMerge(lo, hi, 1, out);
}

}  // namespace

std::vector<CompareExchange> oddEvenMergeSortNetwork(int n) {
  if (n < 2 || n > (1 << 12) || (n & (n - 1)) != 0)
    throw UsageError("sorting network: expected a power of two from 2 to 4096 elements, got " + std::to_string(n));
  std::vector<CompareExchange> network;
  oddEvenMergeSort(0, n - 1, network);
  return network;
}

std::string networkGlsl(const std::vector<CompareExchange>& network) {
  std::string text;
  for (const auto& [i, j] : network) text += "CX(" + std::to_string(i) + ", " + std::to_string(j) + "); ";
  return text;
}

}  // namespace cloudlut::render
