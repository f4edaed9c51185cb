#include "bake/HugePageBuffer.h"

#include <algorithm>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace cloudlut::bake {

namespace {
constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;
}  // namespace

void HugePageFree::operator()(void* p) const { std::free(p); }

HugePageMemory allocateHugePageMemory(std::size_t bytes) {
  // aligned_alloc needs a size that is a multiple of the alignment: round up to whole pages.
  const std::size_t pages = (std::max<std::size_t>(bytes, 1) + kHugePageBytes - 1) / kHugePageBytes;
  const std::size_t size = pages * kHugePageBytes;
  void* p = std::aligned_alloc(kHugePageBytes, size);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  // Advice only: a kernel that refuses it leaves the memory in ordinary pages.
  (void)::madvise(p, size, MADV_HUGEPAGE);
#endif
  return HugePageMemory(p);
}

}  // namespace cloudlut::bake
