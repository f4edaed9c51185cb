#pragma once
// Vector operations on the fields of the fast multiple-scattering method: parallel with oneTBB
// and independent of the number of threads (fixed blocks, summed in order).
#include <vector>

namespace cloudlut::bake {

// Σ_i a[i]·b[i] in double: fixed 4096-element blocks, each summed in order, then the blocks
// in order.
double dot(const std::vector<float>& a, const std::vector<float>& b);

// Σ_i a[i] in double, in the same fixed blocks as dot.
double total(const std::vector<float>& a);

// y ← y + α·x.
void axpy(float alpha, const std::vector<float>& x, std::vector<float>& y);

}  // namespace cloudlut::bake
