#pragma once
// Raw memory for large arrays, in transparent huge pages where the kernel offers them.
//
// A 10⁸-byte array in 4 KiB pages costs the kernel 25 000 page faults on first touch (each a
// trap, on a virtual machine an exit to the hypervisor, and a page clearing); perf of the default
// bake put 6% of its samples in that path. Aligned to 2 MiB and marked MADV_HUGEPAGE, the same
// array is mapped in 2 MiB pages: 50 faults, and fewer TLB misses when it is read. Where huge
// pages are unavailable (another OS, THP "never") the memory is ordinary: only speed differs.
#include <cstddef>
#include <memory>

namespace cloudlut::bake {

struct HugePageFree {
  void operator()(void* p) const;
};
using HugePageMemory = std::unique_ptr<void, HugePageFree>;

// At least `bytes` bytes (contents unspecified), 2 MiB-aligned, advised for huge pages; throws
// std::bad_alloc when the memory cannot be had.
HugePageMemory allocateHugePageMemory(std::size_t bytes);

}  // namespace cloudlut::bake
