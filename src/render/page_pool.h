// Memory for the renderer's per-frame buffers (vertices, triangle records, bins), taken from
// 2 MiB-aligned regions that the kernel is asked to back with huge pages (MADV_HUGEPAGE).
//
// A frame reads and writes some 20 MB spread over these buffers: with 4 KiB pages that is more
// than the TLB maps, and setup and the tile stage pay page walks (docs/perf-notes/frame-stages.md
// measures it).
// Blocks come in power-of-two sizes from 64 bytes (so every block is cache-line aligned); freed
// blocks wait on a list for the next request of their size and are not returned to the system,
// except blocks over 1 MiB, which are mappings of their own. The buffers only grow, so after the
// first frames a frame takes nothing from here.
#pragma once

#include <cstddef>
#include <vector>

namespace tessera::render {

// A block of at least `bytes`, aligned to 64 bytes; thread-safe. Throws std::bad_alloc when the
// system has no memory left.
void* poolAllocate(size_t bytes);
// Gives back a block from poolAllocate with the same `bytes`.
void poolFree(void* block, size_t bytes) noexcept;

// Asks for huge pages for the whole 2 MiB pages inside [memory, memory + bytes), for a large
// buffer allocated elsewhere (the frame's colour): only pages not yet touched get them.
void adviseHugePages(void* memory, size_t bytes) noexcept;

template <class T>
struct PoolAllocator {
  using value_type = T;
  PoolAllocator() = default;
  template <class U>
  PoolAllocator(const PoolAllocator<U>&) noexcept {}
  T* allocate(size_t n) { return static_cast<T*>(poolAllocate(n * sizeof(T))); }
  void deallocate(T* p, size_t n) noexcept { poolFree(p, n * sizeof(T)); }
  friend bool operator==(PoolAllocator, PoolAllocator) { return true; }
};

template <class T>
using PoolVector = std::vector<T, PoolAllocator<T>>;

}  // namespace tessera::render
