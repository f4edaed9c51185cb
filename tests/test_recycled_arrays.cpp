// RecycledArrays (bake/RecycledArrays.h): an array given back is handed out again (so its pages
// are mapped once per bake), the smallest that fits first, and a lease that moves gives back once.
#include <catch2/catch.hpp>

#include <atomic>
#include <cstdint>
#include <cstring>
#include <thread>
#include <vector>

#include "bake/HugePageBuffer.h"
#include "bake/RecycledArrays.h"

using cloudlut::bake::RecycledArrays;

TEST_CASE("recycled arrays: returned arrays are reused, the smallest that fits first", "[bake][pool]") {
  RecycledArrays<float> pool;
  const float* big = nullptr;
  const float* small = nullptr;
  {
    auto a = pool.acquire(1000);
    auto b = pool.acquire(100);
    big = a.data();
    small = b.data();
    CHECK(a.size() == 1000);
    CHECK(b.size() == 100);
  }
  {
    auto c = pool.acquire(50);  // both fit: the smaller one
    CHECK(c.data() == small);
    CHECK(c.size() == 100);
    auto d = pool.acquire(500);  // only the larger fits
    CHECK(d.data() == big);
    auto e = pool.acquire(2000);  // none fits: a new one
    CHECK(e.data() != big);
    CHECK(e.data() != small);
    CHECK(e.size() == 2000);
    auto moved = std::move(d);  // a moved lease gives its array back once, when the new owner ends
    CHECK(d.data() == nullptr);
    CHECK(moved.data() == big);
  }
  // All three are free again: two requests of 1000 get the 1000 and the 2000 arrays.
  auto f = pool.acquire(1000);
  auto g = pool.acquire(1000);
  CHECK(f.data() == big);
  CHECK(g.size() == 2000);
}

TEST_CASE("recycled arrays: leases taken and returned from several threads", "[bake][pool]") {
  RecycledArrays<int> pool;
  std::atomic<bool> ok{true};  // Catch2's assertions are not thread-safe: checked after the join
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&pool, &ok, t] {
      for (int i = 0; i < 200; ++i) {
        auto lease = pool.acquire(static_cast<std::size_t>(64 + (i + t) % 7));
        for (std::size_t k = 0; k < lease.size(); ++k) lease.data()[k] = t;  // each lease is its own
        for (std::size_t k = 0; k < lease.size(); ++k)
          if (lease.data()[k] != t) ok = false;
      }
    });
  for (auto& th : threads) th.join();
  CHECK(ok);
}

TEST_CASE("huge-page memory: 2 MiB-aligned, writable to its last byte, any size", "[bake][pool]") {
  const std::size_t mib = std::size_t{1} << 20;
  for (const std::size_t bytes : {std::size_t{0}, std::size_t{1}, 3 * mib, 2 * mib + 7}) {
    const cloudlut::bake::HugePageMemory m = cloudlut::bake::allocateHugePageMemory(bytes);
    REQUIRE(m);
    CHECK(reinterpret_cast<std::uintptr_t>(m.get()) % (std::uintptr_t{2} << 20) == 0);
    if (bytes > 0) {
      std::memset(m.get(), 0xab, bytes);
      CHECK(static_cast<const unsigned char*>(m.get())[bytes - 1] == 0xab);
    }
  }
}

TEST_CASE("recycled arrays: a minimum size makes one array serve every smaller request", "[bake][pool]") {
  RecycledArrays<float> pool;
  pool.setMinimumSize(1000);
  const float* first = nullptr;
  {
    auto a = pool.acquire(100);  // new: allocated at the minimum size
    CHECK(a.size() == 1000);
    first = a.data();
  }
  auto b = pool.acquire(900);  // fits the array the small request made
  CHECK(b.data() == first);
  auto c = pool.acquire(2000);  // larger than the minimum: its own size
  CHECK(c.size() == 2000);
}
