#include "core/Table4D.h"
#include "core/Errors.h"
#include "core/Glsl.h"
#include "cloudlut_quadrilinear.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cloudlut {

double Axis::value(int i) const {
  if (size <= 1) return min;
  const double x = static_cast<double>(i) / (size - 1);
  const double y = warp > 0.0 ? glsl::concentratedFraction(static_cast<float>(x), static_cast<float>(warp)) : x;
  return min + (max - min) * y;
}

Table4D::Table4D(std::string name, std::array<Axis, 4> axes, std::vector<Channel> channels)
    : name_(std::move(name)), axes_(std::move(axes)), channels_(std::move(channels)) {
  for (const Axis& a : axes_)
    if (a.size < 1) throw std::invalid_argument("table axis '" + a.name + "' has no nodes");
  if (channels_.empty()) throw std::invalid_argument("table '" + name_ + "' has no channels");
  data_.assign(nodeCount() * channels_.size(), 0.0f);
}

std::array<int, 4> Table4D::dims() const {
  return {axes_[0].size, axes_[1].size, axes_[2].size, axes_[3].size};
}

std::size_t Table4D::nodeCount() const {
  std::size_t n = 1;
  for (const Axis& a : axes_) n *= static_cast<std::size_t>(a.size);
  return n;
}

void Table4D::sample(const std::array<float, 4>& x, float* out) const {
  const std::uint32_t dims[4] = {static_cast<std::uint32_t>(axes_[0].size), static_cast<std::uint32_t>(axes_[1].size),
                                 static_cast<std::uint32_t>(axes_[2].size), static_cast<std::uint32_t>(axes_[3].size)};
  cloudlut_reader::sampleQuadrilinear(data_.data(), dims, channels_.size(), x.data(), out);
}

std::uint64_t Table4D::bytesFor(const std::array<int, 4>& dims, int channels) {
  long double n = channels;
  for (int d : dims) n *= d;
  n *= sizeof(float);
  return n > 1.8e19L ? UINT64_MAX : static_cast<std::uint64_t>(n);
}

void checkTableFitsInMemory(const std::array<int, 4>& dims, int channels, int tableCount) {
  for (int d : dims)
    if (d < 2) throw UsageError("every table dimension must be at least 2");
  const long double need = static_cast<long double>(Table4D::bytesFor(dims, channels)) * tableCount;
  const long double pages = static_cast<long double>(sysconf(_SC_PHYS_PAGES));
  const long double pageSize = static_cast<long double>(sysconf(_SC_PAGESIZE));
  const long double budget = pages > 0 && pageSize > 0 ? 0.75L * pages * pageSize : 4.0e9L;
  if (need > budget) {
    throw UsageError(
        "tables of " + std::to_string(dims[0]) + "x" + std::to_string(dims[1]) + "x" +
        std::to_string(dims[2]) + "x" + std::to_string(dims[3]) + " would need " +
        std::to_string(static_cast<long long>(need / 1048576.0L)) + " MiB, more than the " +
        std::to_string(static_cast<long long>(budget / 1048576.0L)) + " MiB this machine can spare");
  }
}

}  // namespace cloudlut
