#include "render/page_pool.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <mutex>
#include <new>

#include <tessera/base/huge_pages.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace tessera::render {
namespace {

constexpr size_t kRegion = kHugePage;
constexpr int kMinClass = 6;   // 64 bytes: a cache line
constexpr int kMaxClass = 20;  // 1 MiB; larger blocks are mappings of their own

size_t roundUp(size_t bytes, size_t unit) {
  return (bytes + unit - 1) / unit * unit;
}

struct FreeBlock {
  FreeBlock* next;
};

struct Pool {
  std::mutex mutex;
  FreeBlock* free[kMaxClass + 1] = {};
  char* next = nullptr;  // the unused rest of the current region
  char* end = nullptr;
};

// Never destroyed: vectors in static objects may give their blocks back after it would be.
Pool& pool() {
  static Pool* const instance = new Pool;
  return *instance;
}

int sizeClass(size_t bytes) {
  return std::max(kMinClass, static_cast<int>(std::bit_width(std::max<size_t>(bytes, 1) - 1)));
}

}  // namespace

void* poolAllocate(size_t bytes) {
  const int k = sizeClass(bytes);
  if (k > kMaxClass) return mapHugePages(roundUp(bytes, kRegion));
  const size_t size = size_t{1} << k;
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  if (FreeBlock* block = p.free[k]) {
    p.free[k] = block->next;
    return block;
  }
  // Blocks are multiples of 64 bytes, so the rest of a region stays line-aligned; what is left
  // at a region's end when a block does not fit is not used.
  if (static_cast<size_t>(p.end - p.next) < size) {
    p.next = static_cast<char*>(mapHugePages(kRegion));
    p.end = p.next + kRegion;
  }
  void* block = p.next;
  p.next += size;
  return block;
}

void adviseHugePages(void* memory, size_t bytes) noexcept {
#if defined(__linux__)
  const uintptr_t begin = roundUp(reinterpret_cast<uintptr_t>(memory), kRegion);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(memory) + bytes) / kRegion * kRegion;
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)memory;
  (void)bytes;
#endif
}

void poolFree(void* block, size_t bytes) noexcept {
  if (block == nullptr) return;
  const int k = sizeClass(bytes);
  if (k > kMaxClass) {
    unmapHugePages(block, roundUp(bytes, kRegion));
    return;
  }
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  FreeBlock* freed = static_cast<FreeBlock*>(block);
  freed->next = p.free[k];
  p.free[k] = freed;
}

}  // namespace tessera::render
