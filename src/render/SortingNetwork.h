#pragma once
// A sorting network: a fixed list of compare-exchanges (i, j), i < j, each of which puts
// elements i and j in order, that sorts any n elements. The volume resolve writes one out in its
// shader (shaders/volume_resolve_sorted.comp.glsl) so that every index is a constant.
#include <string>
#include <utility>
#include <vector>

namespace cloudlut::render {

using CompareExchange = std::pair<int, int>;

// Batcher's odd–even merge sort of n elements, n a power of two ≥ 2 (UsageError otherwise):
// n/4 · log2 n · (log2 n − 1) + n − 1 compare-exchanges (63 for 16, 191 for 32).
std::vector<CompareExchange> oddEvenMergeSortNetwork(int n);

// The network as GLSL text: "CX(i, j); " for each compare-exchange, in order.
std::string networkGlsl(const std::vector<CompareExchange>& network);

}  // namespace cloudlut::render
