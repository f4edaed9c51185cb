#pragma once
// Large arrays kept between uses. A fresh allocation of 10⁸ bytes is mapped by the kernel page
// by page on first touch (a fault and a page clearing per 4 KiB); when every density slice of
// a bake built its transport stencil in a fresh array, that was about 15% of the default bake's
// CPU time (perf, 2026-12-02). Arrays returned to the pool are handed out again, so each is
// mapped once per bake, and in huge pages where the kernel offers them (HugePageBuffer.h).
// Thread-safe: the density slices run side by side.
//
// T must be trivially copyable: arrays come back uninitialised (or holding an earlier user's
// values), like `new T[n]`; n·sizeof(T) must not overflow.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <mutex>
#include <type_traits>
#include <utility>
#include <vector>

#include "bake/HugePageBuffer.h"

namespace cloudlut::bake {

template <class T>
class RecycledArrays {
  static_assert(std::is_trivially_copyable_v<T>, "RecycledArrays holds plain data only");

 public:
  // An array of at least n elements, uninitialised; goes back to the pool when destroyed.
  class Lease {
   public:
    Lease() = default;
    Lease(Lease&& o) noexcept { *this = std::move(o); }
    Lease& operator=(Lease&& o) noexcept {
      if (this != &o) {
        release();
        pool_ = std::exchange(o.pool_, nullptr);
        data_ = std::move(o.data_);
        size_ = std::exchange(o.size_, 0);
      }
      return *this;
    }
    ~Lease() { release(); }
    T* data() const { return static_cast<T*>(data_.get()); }
    std::size_t size() const { return size_; }

   private:
    friend class RecycledArrays;
    void release() {
      if (pool_ && data_) pool_->giveBack(std::move(data_), size_);
      pool_ = nullptr;
    }
    RecycledArrays* pool_ = nullptr;
    HugePageMemory data_;
    std::size_t size_ = 0;
  };

  // New arrays get at least n elements from now on: a pool whose users ask for several sizes
  // (thin and dense density slices) then holds as many arrays as run at once, not one per size.
  // Pages are mapped on first touch, so an array larger than its first user costs nothing more.
  void setMinimumSize(std::size_t n) {
    const std::lock_guard<std::mutex> lock(mutex_);
    minimum_ = n;
  }

  // The smallest free array of at least n elements, or a new one of max(n, minimum size).
  Lease acquire(std::size_t n) {
    Lease lease;
    lease.pool_ = this;
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      std::size_t best = free_.size();
      for (std::size_t i = 0; i < free_.size(); ++i)
        if (free_[i].second >= n && (best == free_.size() || free_[i].second < free_[best].second)) best = i;
      if (best != free_.size()) {
        lease.data_ = std::move(free_[best].first);
        lease.size_ = free_[best].second;
        free_.erase(free_.begin() + static_cast<std::ptrdiff_t>(best));
        return lease;
      }
      n = std::max(n, minimum_);
    }
    lease.data_ = allocateHugePageMemory(n * sizeof(T));
    lease.size_ = n;
    return lease;
  }

 private:
  void giveBack(HugePageMemory data, std::size_t n) {
    const std::lock_guard<std::mutex> lock(mutex_);
    free_.emplace_back(std::move(data), n);
  }

  std::mutex mutex_;
  std::vector<std::pair<HugePageMemory, std::size_t>> free_;
  std::size_t minimum_ = 0;
};

}  // namespace cloudlut::bake
