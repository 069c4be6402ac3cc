// Counts heap allocations while a test asks for it (the no-allocation-per-frame tests). Replaces the
// global operator new and delete: include it in one source file of a test executable.
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

// Counts heap allocations while a test asks for it (for the no-allocation-per-frame test).
static std::atomic<bool> g_count_allocations{false};
static std::atomic<size_t> g_allocations{0};

// A place for a debugger's breakpoint: every counted allocation passes here.
__attribute__((noinline)) void countedAllocation() {
  g_allocations.fetch_add(1);
}

void* operator new(size_t size) {
  if (g_count_allocations.load(std::memory_order_relaxed)) countedAllocation();
  if (void* p = std::malloc(size ? size : 1)) return p;
  throw std::bad_alloc();
}
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

// Runs `frames` twice and returns the heap allocations of the second run: buffers grow to the
// largest frame in the first, then must stay.
template <typename Frames>
size_t allocationsAfterWarmUp(Frames&& frames) {
  frames();
  g_allocations = 0;
  g_count_allocations = true;
  frames();
  g_count_allocations = false;
  return g_allocations.load();
}
