#pragma once
// Counts heap allocations by replacing the global operator new: include it in exactly one source
// file of a test binary of its own (the sanitizers own operator new, so such binaries are left out
// of sanitizer builds). heap_allocations() is the count so far.

#include <atomic>
#include <cstdlib>
#include <new>

namespace netmc::testing {
inline std::atomic<long>& allocation_count() {
  static std::atomic<long> count{0};
  return count;
}
inline long heap_allocations() { return allocation_count().load(); }
}  // namespace netmc::testing

void* operator new(std::size_t size) {
  netmc::testing::allocation_count().fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
