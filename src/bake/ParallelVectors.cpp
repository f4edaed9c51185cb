#include "bake/ParallelVectors.h"

#include <algorithm>
#include <cstddef>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace cloudlut::bake {

double dot(const std::vector<float>& a, const std::vector<float>& b) {
  const std::size_t n = a.size(), block = 4096, nb = (n + block - 1) / block;
  std::vector<double> part(nb, 0.0);
  tbb::parallel_for(std::size_t(0), nb, [&](std::size_t k) {
    double s = 0.0;
    const std::size_t e = std::min(n, (k + 1) * block);
    for (std::size_t i = k * block; i < e; ++i) s += static_cast<double>(a[i]) * b[i];
    part[k] = s;
  });
  double s = 0.0;
  for (double p : part) s += p;
  return s;
}

double total(const std::vector<float>& a) {
  const std::size_t n = a.size(), block = 4096, nb = (n + block - 1) / block;
  std::vector<double> part(nb, 0.0);
  tbb::parallel_for(std::size_t(0), nb, [&](std::size_t k) {
    double s = 0.0;
    const std::size_t e = std::min(n, (k + 1) * block);
    for (std::size_t i = k * block; i < e; ++i) s += a[i];
    part[k] = s;
  });
  double s = 0.0;
  for (double p : part) s += p;
  return s;
}

void axpy(float alpha, const std::vector<float>& x, std::vector<float>& y) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, y.size(), 8192), [&](const auto& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) y[i] += alpha * x[i];
  });
}

}  // namespace cloudlut::bake
